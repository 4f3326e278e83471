#include "scene/import_values.h"

#include "scene/input_limits.h"
#include "scene/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tl::scene {

void ImportValues::fail(const std::string& what) const { throw SceneError(fmt::format("{}: {}", file_.string(), what)); }

void ImportValues::warn(const std::string& what) { warnings_.push_back(fmt::format("{}: {}", file_.string(), what)); }

float ImportValues::finite(double v, const std::string& what) const {
  // Converted first: 1e39 is a finite double and an infinite float.
  const float f = float(v);
  if (!std::isfinite(f)) fail(fmt::format("{} is {}, not a finite number (as a 32-bit float)", what, v));
  return f;
}

float ImportValues::clamped(double v, float lo, float hi, const std::string& what) {
  const float f = finite(v, what);
  if (f >= lo && f <= hi) return f;
  const float c = std::clamp(f, lo, hi);
  warn(fmt::format("{} is {}, outside [{}, {}]; using {}", what, f, lo, hi, c));
  return c;
}

float ImportValues::light(double v, const std::string& what) {
  const float f = finite(v, what);
  if (f >= 0.0f) return f;
  warn(fmt::format("{} is negative ({}); negative light does not exist, using 0", what, f));
  return 0.0f;
}

glm::vec3 ImportValues::lightColor(const std::vector<double>& v, const glm::vec3& fallback, const std::string& what) {
  if (v.empty()) return fallback;
  if (v.size() != 3) fail(fmt::format("{} has {} components, not 3", what, v.size()));
  const glm::vec3 c(finite(v[0], what), finite(v[1], what), finite(v[2], what));
  if (glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f)))) return c;
  warn(fmt::format("{} is negative ({}, {}, {}); negative light does not exist, using 0 there", what, c.x, c.y, c.z));
  return glm::max(c, glm::vec3(0.0f));
}

void ImportValues::requireLightRange(const glm::vec3& v, const std::string& what) const {
  const float most = std::max({v.x, v.y, v.z});
  if (!(most <= InputLimits::kMaxLight))
    fail(fmt::format("{} reaches {:g}, above the {:g} a light or emission may have", what, most, InputLimits::kMaxLight));
}

float ImportValues::morphWeight(double v, const std::string& what) const {
  const float f = finite(v, what);
  if (std::abs(f) > InputLimits::kMaxMorphWeight)
    fail(fmt::format("{} is {:g}, beyond the +-{:g} a morph weight may have", what, f, InputLimits::kMaxMorphWeight));
  return f;
}

}  // namespace tl::scene
