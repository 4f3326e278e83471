// The legacy voxels' optical-depth encoding (shaders/shared/legacy.h), compiled as C++: the
// property that keeps light out of closed rooms, checked on the fetches a cone makes.
#include "shared/legacy.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tl::shared {
namespace {

// A cone stepping one texel at a time along an axis through a solid texel with empty texels
// on both sides: consecutive fetches fall at offsets f - 1 and f from the texel's centre and
// see it with linear weights. Their composited transmittance, as cones.comp composites.
double transmittanceThroughOneSolidTexel(double f, bool opticalDepth) {
  double transmittance = 1.0;
  for (double x : {f - 1.0, f}) {
    const double weight = std::max(0.0, 1.0 - std::abs(x));  // linear filtering of a single solid texel
    const double opacity = opticalDepth ? tlLegacyOpacity(float(weight * 1.0))  // stored depth 1: solid
                                        : weight;                               // stored opacity 1
    transmittance *= 1.0 - opacity;
  }
  return transmittance;
}

TEST(LegacyVoxels, AWallOneTexelThickStopsTheConeWhereverTheFetchesFall) {
  double worstOpacity = 0.0, worstDepth = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double f = i / 100.0;
    worstOpacity = std::max(worstOpacity, transmittanceThroughOneSolidTexel(f, false));
    worstDepth = std::max(worstDepth, transmittanceThroughOneSolidTexel(f, true));
  }
  EXPECT_NEAR(worstOpacity, 0.25, 1e-9) << "filtered opacities let a quarter through (f = 1/2)";
  EXPECT_NEAR(worstDepth, std::exp(-double(kLegacyOpaqueDepth)), 1e-6) << "filtered depths add up to the whole wall's";
  EXPECT_LT(worstDepth, 1e-3);
}

TEST(LegacyVoxels, EncodingRoundTripsAndSolidIsOne) {
  EXPECT_FLOAT_EQ(tlLegacyDepth(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(tlLegacyDepth(0.0f), 0.0f);
  EXPECT_NEAR(tlLegacyOpacity(1.0f), 1.0f - std::exp(-kLegacyOpaqueDepth), 1e-7);
  for (float a : {0.05f, 0.3f, 0.5f, 0.9f, 0.99f}) {
    const vec4 v = tlLegacyVoxelFromPremultiplied(vec4(0.2f * a, 0.4f * a, 0.8f * a, a));
    const vec4 back = tlLegacyVoxelToPremultiplied(v);
    EXPECT_NEAR(back.w, a, 1e-5f);
    EXPECT_NEAR(back.x / back.w, 0.2f, 1e-5f) << "the radiance survives";
    EXPECT_NEAR(v.x / v.w, 0.2f, 1e-5f) << "stored radiance x depth divides back";
  }
}

// The mips composite front to back along the axis: a lit voxel behind an unlit solid one
// stays hidden from that side, and shows from the other.
TEST(LegacyVoxels, OverKeepsTheFarSideHiddenBehindASolidVoxel) {
  const vec4 unlitSolid(0.0f, 0.0f, 0.0f, 1.0f), litSolid(5.0f, 5.0f, 5.0f, 1.0f), empty(0.0f);
  EXPECT_LT(tlLegacyVoxelOver(unlitSolid, litSolid).x, 5.0f * 1e-3f);
  EXPECT_NEAR(tlLegacyVoxelOver(litSolid, unlitSolid).x, 5.0f, 0.01f);
  const vec4 behindEmpty = tlLegacyVoxelOver(empty, litSolid);
  EXPECT_NEAR(behindEmpty.x, 5.0f * tlLegacyOpacity(1.0f), 1e-5f);
  EXPECT_NEAR(behindEmpty.w, tlLegacyOpacity(1.0f), 1e-6f);
}

}  // namespace
}  // namespace tl::shared
