// An environment map (shaders/shared/environment.h): an equirectangular EXR or Radiance HDR
// image of the radiance arriving from every direction, read through OpenImageIO at full float
// precision (a sun in an HDRI is far above half floats' 65504), and what the GPU needs from it:
// the importance table the reference samples it with, and its projection on nine spherical
// harmonics the real-time paths shade with. Lighting data, like the sun and the sky: the CLI's
// --environment places it (session::Lighting), not the glTF (which has no environment).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace tl::scene {

struct EnvironmentMap {
  std::filesystem::path path;
  uint32_t width = 0, height = 0;
  std::vector<glm::vec3> radiance;  // width * height, row 0 at the zenith, as stored (linear)
  uint64_t contentHash = 0;         // of the texels and the size
  glm::vec3 meanRadiance{0.0f};     // over the sphere (by solid angle): the uniform sky of the same irradiance budget
};

// Reads `file` (EXR, HDR or any float image OpenImageIO reads; grey is taken as white light)
// within InputLimits' image limits. Throws SceneError naming the file on anything unusable:
// not an image, too large, a negative or non-finite texel, a texel above InputLimits::kMaxLight.
EnvironmentMap loadEnvironmentMap(const std::filesystem::path& file);

// A map from texels given in memory (tests, content generation); checks as loadEnvironmentMap.
EnvironmentMap makeEnvironmentMap(uint32_t width, uint32_t height, std::vector<glm::vec3> radiance);

// Solid angle of a texel of row `row`: (2 pi / W) (cos theta0 - cos theta1).
double environmentTexelSolidAngle(const EnvironmentMap& map, uint32_t row);

// The table of shared/environment.h (texels, marginal and conditional CDFs) as floats.
std::vector<float> environmentTable(const EnvironmentMap& map);

// The radiance's projection on the nine SH basis functions of shared/environment.h, in world
// directions (the map turned by `rotationRadians` about +Y) and scaled by `intensity`, each
// texel integrated over its exact solid angle (FrameConstants::envSh; shared/environment.h
// tlEnvShIrradiance and tlEnvShRadiance evaluate them).
std::array<glm::vec4, 9> environmentSh9(const EnvironmentMap& map, float rotationRadians, float intensity);

// A sun inside an environment map: a small patch of texels far brighter than the rest of the sky.
struct EnvironmentSun {
  glm::dvec3 direction{0.0, 1.0, 0.0};  // towards it, in the map's frame (unit)
  glm::vec3 irradiance{0.0f};           // sum of L x solid angle over its texels (before the map's intensity)
  double angularRadius = 0.0;           // of a disc of its solid angle, radians
  uint32_t texels = 0;
};
struct SunAndSky {
  EnvironmentSun sun;
  std::shared_ptr<const EnvironmentMap> sky;  // the map without the sun: its texels hold the sky around it
};

// The real-time paths read a map through order-2 spherical harmonics, which spread a sun over
// the whole sphere (and ring below zero opposite it); a sun separated from its map can be shaded
// as what it is, a shadowed directional light of its size. Found when the brightest texel is at
// least kSunContrast times the map's mean luminance and the texels within kSunSearchRadius of it
// brighter than a twentieth of it carry at least kSunShare of the map's light (by solid angle);
// the sky keeps everything else. Empty when there is no such sun (an overcast or uniform map).
inline constexpr double kSunContrast = 50.0;
inline constexpr double kSunSearchRadius = 0.14;  // radians (8 degrees)
inline constexpr double kSunShare = 0.2;
std::optional<SunAndSky> separateEnvironmentSun(const EnvironmentMap& map);

}  // namespace tl::scene
