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

}  // namespace tl::scene
