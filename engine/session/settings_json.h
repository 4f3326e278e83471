// Render settings from JSON (compare --settings, capture manifests): each key names one
// RenderSettings field, with the field's name; an unknown key or a value of the wrong type is
// one clear error that names it, and nothing is applied.
#pragma once

#include "lighting/common/frame_inputs.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace tl::session {

// JSON text of settings (--set, a --settings file, a manifest), parsed under the nesting limit
// of scene/input_limits.h; SessionError naming `what` when it is not JSON.
nlohmann::json parseSettingsText(std::string_view text, const std::string& what);

// Returns `base` with the keys of `overrides` (an object) applied.
lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides);
// Every setting applySettingsJson knows, with its value, plus the image size: what a capture
// manifest records, and what applySettingsJson takes back (less width and height).
nlohmann::json settingsJson(const lighting::RenderSettings& settings);

}  // namespace tl::session
