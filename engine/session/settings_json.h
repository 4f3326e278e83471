// Render settings from JSON (compare --settings, capture manifests): each key names one
// RenderSettings field, with the field's name; an unknown key or a value of the wrong type is
// one clear error that names it, and nothing is applied.
#pragma once

#include "lighting/common/frame_inputs.h"

#include <nlohmann/json.hpp>

namespace tl::session {

// Returns `base` with the keys of `overrides` (an object) applied.
lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides);
// Every setting applySettingsJson knows, with its value, plus the image size: what a capture
// manifest records, and what applySettingsJson takes back (less width and height).
nlohmann::json settingsJson(const lighting::RenderSettings& settings);

}  // namespace tl::session
