// Render settings as JSON and as `key=value` text, from the one schema
// (lighting/common/render_settings.h): each key names one setting; an unknown key, a value of
// the wrong type or one outside the setting's range (checked after conversion to the type it is
// stored in) is one clear error that names it, and nothing is applied.
#pragma once

#include "lighting/common/render_settings.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace tl::session {

// JSON text of settings (--set, a --settings file, a manifest), parsed under the nesting limit
// of scene/input_limits.h; SessionError naming `what` when it is not JSON.
nlohmann::json parseSettingsText(std::string_view text, const std::string& what);

// Returns `base` with the keys of `overrides` (an object) applied.
lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides);
// Returns `base` with one `name=value` applied ("shadowMapSize=4096", "materials=clay",
// "rtDenoise=false"): what `--set` takes on every subcommand that renders.
lighting::RenderSettings applySettingText(const lighting::RenderSettings& base, std::string_view assignment);
// Every setting of the schema with its value (the image size included): what capture
// manifests, bench JSON and compare reports record, and what applySettingsJson takes back.
nlohmann::json settingsJson(const lighting::RenderSettings& settings);
// The settings object of a JSON file: a plain object of settings, or any file Twinlight writes
// that records them under "settings" (a capture manifest, bench JSON, a compare report); with
// `allowList`, a JSON array (compare's list of configurations) is returned as it is.
nlohmann::json readSettingsFile(const std::filesystem::path& file, bool allowList = false);

}  // namespace tl::session
