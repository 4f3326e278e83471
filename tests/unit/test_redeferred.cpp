// Redeferred shading's factorisation (shaders/shared/redeferred.h) against the BRDF it splits
// (shared/shading.h): a light summed into the material-free I-buffer and resolved against a
// material gives back the BRDF's radiance, for every material, roughness and direction on a
// grid; so does uniform irradiance through the diffuse layer. The sums must not depend on the
// material (they are computed without it), and a white Lambert surface under the "light only"
// view shows E / pi.
#include "shared/redeferred.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tl::shared {
namespace {

vec3 direction(float theta, float phi) {
  return vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// |a - b| per channel against the larger, with a floor for values near 0.
void expectClose(vec3 a, vec3 b, float rel, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], rel * std::max({std::abs(a[c]), std::abs(b[c]), 1e-4f})) << what << " channel " << c;
}

TEST(Redeferred, ALightResolvesToTheBrdfsRadiance) {
  const vec3 n(0.0f, 0.0f, 1.0f), irradiance(2.0f, 1.0f, 0.5f);
  const vec3 colours[] = {vec3(1.0f), vec3(0.9f, 0.5f, 0.1f), vec3(0.02f, 0.3f, 0.8f), vec3(0.0f)};
  int cases = 0;
  for (uint materials : {kMaterialsAuthored, kMaterialsDiffuse, kMaterialsClay})
    for (float roughness : {0.05f, 0.2f, 0.5f, 0.8f, 1.0f})
      for (float metallic : {0.0f, 0.5f, 1.0f})
        for (const vec3& colour : colours)
          for (float tv : {0.0f, 0.6f, 1.2f, 1.5f})
            for (float tl : {0.1f, 0.7f, 1.3f, 1.55f})
              for (float phi : {0.0f, 1.0f, 3.14159f}) {
                const vec3 v = direction(tv, 0.3f), l = direction(tl, phi);
                const SurfaceParams s = tlMaterialSurface(colour, roughness, metallic, materials);
                const SurfaceParams g = tlIbufferSurface(tlMaterialRoughness(roughness, materials), materials);
                const float nl = dot(n, l);
                const IbufferSums sums = tlIbufferAddLight(tlIbufferZero(), g, n, v, l, irradiance * nl);
                const vec3 deferred = tlBrdf(s, n, v, l) * irradiance * nl;
                expectClose(tlIbufferResolve(s, dot(n, v), sums), deferred, 1e-5f, "light");
                ++cases;
              }
  EXPECT_EQ(cases, 3 * 5 * 3 * 4 * 4 * 4 * 3);
}

TEST(Redeferred, UniformIrradianceResolvesToTheEnvironmentDiffuse) {
  const vec3 e(3.0f, 2.0f, 1.0f);
  for (uint materials : {kMaterialsAuthored, kMaterialsClay})
    for (float roughness : {0.05f, 0.3f, 1.0f})
      for (float nv : {0.01f, 0.5f, 1.0f}) {
        const SurfaceParams s = tlMaterialSurface(vec3(0.7f, 0.5f, 0.2f), roughness, 0.3f, materials);
        const SurfaceParams g = tlIbufferSurface(tlMaterialRoughness(roughness, materials), materials);
        const IbufferSums sums = tlIbufferAddIrradiance(tlIbufferZero(), g, e);
        expectClose(tlIbufferResolve(s, nv, sums), tlEnvironmentDiffuse(s, nv) * kInvPi * e, 1e-5f, "irradiance");
      }
}

// A white Lambertian surface reflects E / pi of any light: the light-only view in the override
// modes; in the authored mode a white dielectric, whose whole albedo is 1 under uniform light.
TEST(Redeferred, LightOnlyIsTheLightOnAWhiteSurface) {
  const vec3 e(1.0f, 2.0f, 4.0f);
  const IbufferSums lambert = tlIbufferAddIrradiance(tlIbufferZero(), tlIbufferSurface(1.0f, kMaterialsClay), e);
  expectClose(tlIbufferLightOnly(1.0f, kMaterialsClay, 0.7f, lambert), e * kInvPi, 1e-6f, "white Lambert");
  for (float roughness : {0.1f, 0.5f, 1.0f}) {
    const SurfaceParams g = tlIbufferSurface(roughness, kMaterialsAuthored);
    const SurfaceParams white = tlSurface(vec3(1.0f), roughness, 0.0f);
    const IbufferSums sums = tlIbufferAddIrradiance(tlIbufferZero(), g, e);
    expectClose(tlIbufferLightOnly(roughness, kMaterialsAuthored, 0.6f, sums), tlEnvironmentDiffuse(white, 0.6f) * kInvPi * e,
                1e-6f, "white dielectric");
  }
}

// The sums hold light, not material: the same light on two very different materials of one
// roughness gives the same sums (the illumination pass never sees the colour), and they are
// additive (two lights sum to the sum of each).
TEST(Redeferred, SumsAreMaterialFreeAndAdditive) {
  const vec3 n(0.0f, 0.0f, 1.0f), v = direction(0.8f, 0.0f), l1 = direction(0.4f, 2.0f), l2 = direction(1.1f, -1.0f);
  const SurfaceParams g = tlIbufferSurface(0.4f, kMaterialsAuthored);
  const IbufferSums a = tlIbufferAddLight(tlIbufferZero(), g, n, v, l1, vec3(1.0f));
  const IbufferSums b = tlIbufferAddLight(tlIbufferZero(), g, n, v, l2, vec3(0.5f));
  const IbufferSums both = tlIbufferAddLight(a, g, n, v, l2, vec3(0.5f));
  for (const SurfaceParams& s : {tlSurface(vec3(0.9f, 0.1f, 0.1f), 0.4f, 0.0f), tlSurface(vec3(0.95f, 0.64f, 0.54f), 0.4f, 1.0f)}) {
    expectClose(tlIbufferResolve(s, dot(n, v), both),
                tlIbufferResolve(s, dot(n, v), a) + tlIbufferResolve(s, dot(n, v), b), 1e-6f, "additive");
    // The sums take the irradiance on the surface (E n.l): 1 and 0.5 here.
    expectClose(tlIbufferResolve(s, dot(n, v), both), tlBrdf(s, n, v, l1) + tlBrdf(s, n, v, l2) * 0.5f, 1e-5f, "two lights");
  }
  // A light from below adds nothing.
  const IbufferSums below = tlIbufferAddLight(tlIbufferZero(), g, n, v, -l1, vec3(1.0f));
  EXPECT_EQ(below.dg, vec3(0.0f));
  EXPECT_EQ(below.sg1, vec3(0.0f));
}

}  // namespace
}  // namespace tl::shared
