// Robust ray origins (shared/ray_origin.h): the offset point is strictly on the normal's
// side of the surface and stays within a few ULPs of it, at any distance from the origin.
#include "shared/ray_origin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tl::shared {
namespace {

TEST(RayOrigin, LeavesTheSurfaceOnTheNormalsSideAtAnyMagnitude) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (float sceneScale : {1e-2f, 10.0f, 1e3f})
    for (float magnitude : {0.0f, 1e-3f, 0.5f, 10.0f, 1e3f, 1e5f, 1e7f}) {
      for (int i = 0; i < 500; ++i) {
        vec3 n = normalize(vec3(unit(rng), unit(rng), unit(rng)));
        vec3 p = vec3(unit(rng), unit(rng), unit(rng)) * magnitude * (sceneScale / 10.0f);
        vec3 o = tlOffsetRayOrigin(p, n, sceneScale);
        // Signed distance along the normal, in double: positive, and small relative to |p| or,
        // near the origin, to the scene.
        double d = double(o.x - p.x) * n.x + double(o.y - p.y) * n.y + double(o.z - p.z) * n.z;
        EXPECT_GT(d, 0.0) << magnitude;
        double scale = std::max(double(std::abs(p.x) + std::abs(p.y) + std::abs(p.z)), double(sceneScale) / 10.0);
        EXPECT_LT(d, 1e-3 * scale) << magnitude;
      }
    }
}

TEST(RayOrigin, NearTheOriginTheOffsetIsAShareOfTheScene) {
  for (float sceneScale : {1e-2f, 10.0f, 1e3f}) {
    vec3 o = tlOffsetRayOrigin(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), sceneScale);
    EXPECT_FLOAT_EQ(o.y, kRayOriginFloatScale * sceneScale);
    EXPECT_EQ(o.x, 0.0f);
  }
  // The same point in a scene a hundred times larger leaves by a hundred times as much.
  const vec3 p(0.01f, -0.02f, 0.005f), n = normalize(vec3(1.0f, 2.0f, 0.5f));
  const vec3 small = tlOffsetRayOrigin(p, n, 10.0f) - p, large = tlOffsetRayOrigin(p * 100.0f, n, 1000.0f) - p * 100.0f;
  EXPECT_NEAR(large.x / small.x, 100.0f, 1.0f);
  EXPECT_NEAR(large.y / small.y, 100.0f, 1.0f);
}

}  // namespace
}  // namespace tl::shared
