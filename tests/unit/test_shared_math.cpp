// The shader math in shaders/shared/, compiled as C++, against closed forms.
#include "shared/color.h"
#include "shared/packing.h"
#include "shared/shading.h"
#include "shared/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tl::shared {
namespace {

TEST(Color, SrgbKnownPointsAndRoundTrip) {
  EXPECT_NEAR(tlLinearToSrgb1(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(tlSrgbToLinear1(0.735357f), 0.5f, 1e-5f);
  EXPECT_EQ(tlLinearToSrgb1(0.0f), 0.0f);
  EXPECT_NEAR(tlLinearToSrgb1(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(tlLinearToSrgb1(0.002f), 0.02584f, 1e-5f);  // linear segment
  for (int i = 0; i <= 1000; ++i) {
    float x = float(i) / 1000.0f;
    EXPECT_NEAR(tlSrgbToLinear1(tlLinearToSrgb1(x)), x, 2e-6f);
  }
}

TEST(Color, YCoCgIsExactlyInvertibleAndGreyHasNoChroma) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 100.0f);  // HDR: the encoding is linear
  for (int i = 0; i < 1000; ++i) {
    vec3 c(u(rng), u(rng), u(rng));
    vec3 back = tlYCoCgToRgb(tlRgbToYCoCg(c));
    EXPECT_NEAR(back.x, c.x, 1e-4f);
    EXPECT_NEAR(back.y, c.y, 1e-4f);
    EXPECT_NEAR(back.z, c.z, 1e-4f);
  }
  vec3 grey = tlRgbToYCoCg(vec3(0.7f));
  EXPECT_NEAR(grey.x, 0.7f, 1e-7f);
  EXPECT_NEAR(grey.y, 0.0f, 1e-7f);
  EXPECT_NEAR(grey.z, 0.0f, 1e-7f);
}

TEST(Tonemap, AcesIsMonotonicBoundedAndBlackStaysBlack) {
  EXPECT_NEAR(tlTonemapAces(vec3(0.0f)).x, 0.0f, 1e-3f);
  float prev = -1.0f;
  for (float x = 0.0f; x < 100.0f; x += 0.05f) {
    float y = tlTonemapAces(vec3(x)).y;
    EXPECT_GE(y, prev - 1e-6f) << x;
    EXPECT_LE(y, 1.0f);
    prev = y;
  }
  EXPECT_GT(tlTonemapAces(vec3(1000.0f)).x, 0.95f);
  // Mid grey lands in the middle of the display range.
  float mid = tlTonemapAces(vec3(0.18f)).y;
  EXPECT_GT(mid, 0.1f);
  EXPECT_LT(mid, 0.3f);
}

TEST(Packing, OctahedralRoundTripIsAccurateEverywhere) {
  // Float round trip is exact to rounding; through 16-bit snorm with plain rounding the
  // worst case is a few hundredths of a degree (Cigolle et al. 2014 report 0.04 deg for
  // oct32 without the precise encoder), far below what shading can show.
  double worst = 0.0, worstFloat = 0.0;
  auto check = [&](vec3 n) {
    n = normalize(n);
    vec2 e = tlOctEncode(n);
    EXPECT_LE(std::abs(e.x), 1.0f);
    EXPECT_LE(std::abs(e.y), 1.0f);
    // Through 16-bit snorm, as stored in gbuffer.normal.
    vec2 q(std::round(e.x * 32767.0f) / 32767.0f, std::round(e.y * 32767.0f) / 32767.0f);
    // atan2(|a x b|, a.b) in double: acos of a float dot near 1 would itself be off by 0.02 deg.
    auto angle = [&](vec3 b) {
      glm::dvec3 a(n), c(b);
      return std::atan2(glm::length(glm::cross(a, c)), glm::dot(a, c)) * 180.0 / M_PI;
    };
    worst = std::max(worst, angle(tlOctDecode(q)));
    worstFloat = std::max(worstFloat, angle(tlOctDecode(e)));
  };
  for (vec3 n : {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                 vec3(1, 1, -1), vec3(-1, -1, -1)})
    check(n);
  const int steps = 200;
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      double theta = M_PI * i / steps, phi = M_PI * j / steps;
      check(vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))));
    }
  EXPECT_LT(worstFloat, 0.002);
  EXPECT_LT(worst, 0.05);
}

TEST(Shading, GgxDistributionIsNormalised) {
  // Integral of D(h) (n.h) over the hemisphere = 1 for any roughness.
  for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f}) {
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      double ct = (i + 0.5) / n;  // cos(theta) uniformly: d(omega) = 2 pi d(cos theta)
      sum += tlGgxD(float(ct), alpha) * ct * 2.0 * M_PI / n;
    }
    EXPECT_NEAR(sum, 1.0, 0.01) << alpha;
  }
}

TEST(Shading, LambertUnderUniformSkyGivesAlbedoTimesL) {
  // Radiance = integral f * L * cos = albedo/pi * pi * L for the diffuse lobe.
  SurfaceParams s = tlSurface(vec3(0.8f), 1.0f, 0.0f);
  vec3 n(0, 0, 1), v(0, 0, 1);
  const int steps = 400;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      double ct = (i + 0.5) / steps, phi = 2 * M_PI * (j + 0.5) / steps, st = std::sqrt(1 - ct * ct);
      vec3 l(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
      sum += double(tlBrdf(s, n, v, l).x) * ct * (2.0 * M_PI / (steps * steps));
    }
  // Diffuse 0.8 plus the dielectric specular lobe, which the split-sum term approximates.
  double expected = 0.8 + double(tlEnvironmentSpecular(s, 1.0f).x);
  EXPECT_NEAR(sum, expected, 0.02);
}

TEST(Shading, MetalsHaveNoDiffuseAndF0IsBaseColour) {
  SurfaceParams s = tlSurface(vec3(1.0f, 0.78f, 0.34f), 0.25f, 1.0f);
  EXPECT_EQ(s.diffuse.x, 0.0f);
  EXPECT_NEAR(s.f0.y, 0.78f, 1e-6f);
  SurfaceParams d = tlSurface(vec3(0.5f), 0.5f, 0.0f);
  EXPECT_NEAR(d.f0.x, 0.04f, 1e-6f);
  EXPECT_NEAR(tlFresnelSchlick(vec3(0.04f), 1.0f).x, 0.04f, 1e-6f);
  EXPECT_NEAR(tlFresnelSchlick(vec3(0.04f), 0.0f).x, 1.0f, 1e-6f);
}

TEST(Shading, EnvironmentSpecularIsBoundedAndFinite) {
  for (float r : {0.0f, 0.25f, 0.5f, 1.0f})
    for (float nv : {1e-4f, 0.1f, 0.5f, 1.0f}) {
      vec3 e = tlEnvironmentSpecular(tlSurface(vec3(1.0f), r, 1.0f), nv);
      EXPECT_TRUE(std::isfinite(e.x));
      EXPECT_GE(e.x, 0.0f);
      EXPECT_LE(e.x, 1.05f);
    }
}

}  // namespace
}  // namespace tl::shared
