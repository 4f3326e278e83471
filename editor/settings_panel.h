// The render settings in the editor, generated from the schema (lighting/common/render_settings.h):
// one widget per setting, grouped by owner (common first, the selected path's open), the
// setting's name as the label (the name `--set` and every settings JSON use), its help, unit,
// range and what it restarts in the tooltip; "Copy settings as JSON", paste, and defaults.
#pragma once

#include <filesystem>
#include <string>

namespace tl::editor {

class EditorApp;

void settingsSection(EditorApp& app);

// Presets (session/presets.h): a built-in one of the current path by name (Fast, Balanced,
// Reference-like), else the artist's <name>.json in presetDirectory(); SessionError when
// neither exists. Saving writes every panel setting as <name>.json there and returns the file.
std::filesystem::path presetDirectory();
void applyNamedPreset(EditorApp& app, const std::string& name);
std::filesystem::path saveNamedPreset(EditorApp& app, const std::string& name);

}  // namespace tl::editor
