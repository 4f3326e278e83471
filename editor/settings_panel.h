// The render settings in the editor, generated from the schema (lighting/common/render_settings.h):
// one widget per setting, grouped by owner (common first, the selected path's open), the
// setting's name as the label (the name `--set` and every settings JSON use), its help, unit,
// range and what it restarts in the tooltip; "Copy settings as JSON", paste, and defaults.
#pragma once

namespace tl::editor {

class EditorApp;

void settingsSection(EditorApp& app);

}  // namespace tl::editor
