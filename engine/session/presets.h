// Named presets of render settings. Built in, per lighting path: Fast, Balanced and
// Reference-like, each a list of schema entries (render_settings.h) and values, applied
// through the schema's checks. An artist's own presets are settings JSON files (every panel
// setting, no image size), which `render --settings` and `compare --settings` read as they are.
#pragma once

#include "lighting/common/render_settings.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tl::session {

struct Preset {
  std::string name;         // "Fast", "Balanced", "Reference-like"
  std::string path;         // the lighting path it is for
  std::string description;  // what it trades, in one line
  std::vector<std::pair<std::string, std::string>> values;  // setting name, value as `--set` takes it
};

// Every built-in preset, per path in the order Fast, Balanced, Reference-like.
const std::vector<Preset>& builtInPresets();
// Returns `base` with the preset applied: every setting any preset of its path names back to
// its default first (so presets do not stack), then the preset's values. Throws
// std::invalid_argument naming a setting the schema does not take.
lighting::RenderSettings applyPreset(const lighting::RenderSettings& base, const Preset& preset);

// The preset as a settings object of its own values, typed as the schema types them
// ({"shadowMapSize": 1024, "softShadows": false}): a `compare` configuration's "settings".
nlohmann::json presetSettingsJson(const Preset& preset);

// An artist's preset: every panel setting as JSON, written atomically (SessionError naming
// the file when it cannot be), read back with readSettingsFile's checks.
void savePresetFile(const std::filesystem::path& file, const lighting::RenderSettings& settings);
lighting::RenderSettings loadPresetFile(const std::filesystem::path& file, const lighting::RenderSettings& base);

}  // namespace tl::session
