// Render settings from JSON (compare --settings, capture manifests): each key names one
// RenderSettings field, with the field's name; an unknown key or a value of the wrong type is
// one clear error that names it, and nothing is applied.
#pragma once

#include "lighting/common/frame_inputs.h"

#include <nlohmann/json.hpp>

namespace tl::session {

// Returns `base` with the keys of `overrides` (an object) applied.
lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides);

}  // namespace tl::session
