// Numbers read from a scene file, checked after conversion to the float they are stored in:
// a value that is not finite (or overflows float) is refused with one error naming it, a
// value outside its stated range is clamped into it with a warning (negative light becomes
// no light, not negative radiance). The ranges are InputLimits' (scene/input_limits.h) and
// the glTF specification's.
#pragma once

#include <glm/glm.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tl::scene {

class ImportValues {
 public:
  ImportValues(const std::filesystem::path& file, std::vector<std::string>& warnings) : file_(file), warnings_(warnings) {}

  // Finite as a float, else SceneError "FILE: WHAT is V, not a finite number".
  float finite(double v, const std::string& what) const;
  // Finite, then clamped into [lo, hi] (a warning when it had to be).
  float clamped(double v, float lo, float hi, const std::string& what);
  // Non-negative light (colour, intensity, emission): finite, negative -> 0 with a warning.
  float light(double v, const std::string& what);
  // Components through light(); `count` values are expected (else `fallback`).
  glm::vec3 lightColor(const std::vector<double>& v, const glm::vec3& fallback, const std::string& what);
  // A radiance, irradiance or intensity as used: each component at most InputLimits::kMaxLight.
  void requireLightRange(const glm::vec3& v, const std::string& what) const;
  // A morph weight: finite and at most InputLimits::kMaxMorphWeight in magnitude.
  float morphWeight(double v, const std::string& what) const;

  [[noreturn]] void fail(const std::string& what) const;
  void warn(const std::string& what);

 private:
  const std::filesystem::path& file_;
  std::vector<std::string>& warnings_;
};

}  // namespace tl::scene
