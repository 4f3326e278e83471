// Checks the RT and legacy tests share: SH irradiance of a read-back pixel, the open plane
// under a uniform sky, and colour bleeding on the Cornell box's floor.
#pragma once

#include "gpu_fixture.h"

#include "shared/packing.h"
#include "shared/sh.h"

#include <string>
#include <vector>

namespace tl::test {

// Irradiance (RGB) of pixel i from an SH luma image and a chroma image of `coCgChannels`
// channels (chroma in the first two), resolved against normal n.
inline glm::vec3 irradianceAt(const std::vector<float>& shY, const std::vector<float>& coCg, uint32_t coCgChannels,
                              size_t i, glm::vec3 n) {
  shared::ShLumaCoCg sh = shared::tlShMake(glm::vec4(shY[4 * i], shY[4 * i + 1], shY[4 * i + 2], shY[4 * i + 3]),
                                           glm::vec2(coCg[coCgChannels * i], coCg[coCgChannels * i + 1]));
  return shared::tlShResolveIrradiance(sh, n);
}

// After a frame on content/plane.gltf that read back the named AO, SH luma and chroma images
// and gbuffer.depth: the worst AO distance from 1 and the worst irradiance error relative to
// pi L (the plane's normal is +y) over the surface pixels.
struct PlaneErrors {
  size_t surface = 0, pixels = 0;
  double worstAo = 0.0, worstIrradiance = 0.0;
  size_t worstAoPixel = 0;
};
inline PlaneErrors planeErrors(session::Session& s, const std::string& ao, const std::string& shY, const std::string& coCg) {
  const glm::vec3 sky = s.lighting().skyRadiance;
  auto a = s.buffer(ao).texels(), y = s.buffer(shY).texels(), c = s.buffer(coCg).texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  const uint32_t channels = s.buffer(coCg).channels();
  PlaneErrors e;
  e.pixels = depth.size();
  for (size_t i = 0; i < depth.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    ++e.surface;
    if (std::abs(double(a[i]) - 1.0) > e.worstAo) e.worstAo = std::abs(double(a[i]) - 1.0), e.worstAoPixel = i;
    glm::vec3 irradiance = irradianceAt(y, c, channels, i, glm::vec3(0, 1, 0));
    for (int k = 0; k < 3; ++k)
      e.worstIrradiance = std::max(e.worstIrradiance, std::abs(irradiance[k] / (shared::kPi * sky[k]) - 1.0));
  }
  return e;
}

// Red-to-green ratio of the irradiance on the Cornell floor in the fifth of its width next to
// each side wall (left: red, right: green), from the named SH images of a 64 x 64 frame.
struct Bleeding {
  double left = 0.0, right = 0.0;
  uint32_t floorWidth = 0;  // pixels between the leftmost and rightmost floor pixel
};
inline Bleeding cornellBleeding(session::Session& s, const std::string& path, const std::string& shYName,
                                const std::string& coCgName, uint32_t frames) {
  const uint32_t w = 64, h = 64;
  s.setPath(path);
  s.setSize(w, h);
  for (const std::string& n : {shYName, coCgName, std::string("gbuffer.normal")}) s.requestBuffer(n);
  s.renderFrames(frames);
  const auto& coCgBuffer = s.buffer(coCgName);
  auto shY = s.buffer(shYName).texels(), coCg = coCgBuffer.texels(), normal = s.buffer("gbuffer.normal").texels();
  uint32_t lo = w, hi = 0;
  std::vector<bool> floor(w * h);
  for (uint32_t i = 0; i < w * h; ++i) {
    glm::vec3 n = shared::tlOctDecode(glm::vec2(normal[2 * i], normal[2 * i + 1]));
    if (n.y > 0.95f) floor[i] = true, lo = std::min(lo, i % w), hi = std::max(hi, i % w);
  }
  glm::dvec3 left(0.0), right(0.0);
  for (uint32_t i = 0; i < w * h; ++i) {
    if (!floor[i]) continue;
    glm::dvec3 e(irradianceAt(shY, coCg, coCgBuffer.channels(), i, glm::vec3(0, 1, 0)));
    if (i % w <= lo + (hi - lo) / 5) left += e;
    if (i % w >= hi - (hi - lo) / 5) right += e;
  }
  return {left.r / left.g, right.r / right.g, hi > lo ? hi - lo : 0};
}

}  // namespace tl::test
