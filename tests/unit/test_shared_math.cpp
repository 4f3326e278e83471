// The shader math in shaders/shared/, compiled as C++, against closed forms.
#include "shared/color.h"
#include "shared/packing.h"
#include "shared/sampling.h"
#include "shared/scene.h"
#include "shared/sh.h"
#include "shared/rt.h"
#include "shared/sh_specular.h"
#include "shared/shading.h"
#include "shared/tonemap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace tl::shared {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Angle between two directions in degrees, in double: acos of a float dot near 1 would itself
// be off by ~0.02 deg.
double angleDeg(vec3 a, vec3 b) {
  glm::dvec3 x(a), y(b);
  return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)) * 180.0 / kPiD;
}

// Fibonacci sphere: n near-uniform directions, each standing for 4 pi / n steradians.
std::vector<vec3> fibonacciSphere(int n) {
  std::vector<vec3> dirs;
  const double golden = kPiD * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
    dirs.emplace_back(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }
  return dirs;
}

std::vector<vec3> randomUnitVectors(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<vec3> v;
  while (int(v.size()) < n) {
    vec3 x(g(rng), g(rng), g(rng));
    if (glm::length(x) > 1e-3f) v.push_back(glm::normalize(x));
  }
  return v;
}

void expectVecNear(vec3 a, vec3 b, float tol, const char* what = "") {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// ---------------------------------------------------------------------------------- colour

TEST(Color, SrgbKnownPointsAndRoundTrip) {
  EXPECT_NEAR(tlLinearToSrgb1(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(tlSrgbToLinear1(0.735357f), 0.5f, 1e-5f);
  EXPECT_EQ(tlLinearToSrgb1(0.0f), 0.0f);
  EXPECT_NEAR(tlLinearToSrgb1(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(tlLinearToSrgb1(0.002f), 0.02584f, 1e-5f);  // linear segment
  EXPECT_NEAR(tlSrgbToLinear1(0.5f), 0.214041f, 1e-5f);
  // The two pieces meet at the breakpoint (the standard's constants are continuous to ~1e-7).
  EXPECT_NEAR(12.92f * 0.0031308f, 1.055f * std::pow(0.0031308f, 1.0f / 2.4f) - 0.055f, 1e-6f);
  float prev = -1.0f;
  for (int i = 0; i <= 1000; ++i) {
    float x = float(i) / 1000.0f;
    EXPECT_NEAR(tlSrgbToLinear1(tlLinearToSrgb1(x)), x, 2e-6f);
    float s = tlLinearToSrgb1(x);
    EXPECT_GT(s, prev);
    prev = s;
  }
  expectVecNear(tlLinearToSrgb(vec3(0.0f, 0.5f, 1.0f)), vec3(0.0f, 0.735357f, 1.0f), 1e-5f);
}

TEST(Color, YCoCgIsExactlyInvertibleAndGreyHasNoChroma) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> ldr(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    vec3 c(ldr(rng), ldr(rng), ldr(rng));
    expectVecNear(tlYCoCgToRgb(tlRgbToYCoCg(c)), c, 1e-6f);
  }
  std::uniform_real_distribution<float> hdr(0.0f, 100.0f);  // HDR: the encoding is linear
  for (int i = 0; i < 1000; ++i) {
    vec3 c(hdr(rng), hdr(rng), hdr(rng));
    expectVecNear(tlYCoCgToRgb(tlRgbToYCoCg(c)), c, 1e-4f);
  }
  vec3 grey = tlRgbToYCoCg(vec3(0.7f));
  EXPECT_NEAR(grey.x, 0.7f, 1e-7f);
  EXPECT_NEAR(grey.y, 0.0f, 1e-7f);
  EXPECT_NEAR(grey.z, 0.0f, 1e-7f);
  // The closed form on the primaries.
  expectVecNear(tlRgbToYCoCg(vec3(1, 0, 0)), vec3(0.25f, 0.5f, -0.25f), 1e-7f);
  expectVecNear(tlRgbToYCoCg(vec3(0, 1, 0)), vec3(0.5f, 0.0f, 0.5f), 1e-7f);
  expectVecNear(tlRgbToYCoCg(vec3(0, 0, 1)), vec3(0.25f, -0.5f, -0.25f), 1e-7f);
}

TEST(Color, LuminanceIsRec709) {
  EXPECT_NEAR(tlLuminance(vec3(1.0f)), 1.0f, 1e-6f);
  EXPECT_NEAR(tlLuminance(vec3(0, 1, 0)), 0.7152f, 1e-7f);
}

TEST(Color, ExposureIsTwoToTheMinusEv) {
  EXPECT_FLOAT_EQ(tlExposureScale(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(tlExposureScale(1.0f), 0.5f);
  EXPECT_FLOAT_EQ(tlExposureScale(-2.0f), 4.0f);
  // A luminance of 2^ev maps to 1.0 (what session's autoExposureEv relies on).
  EXPECT_NEAR(std::exp2(5.3f) * tlExposureScale(5.3f), 1.0f, 1e-6f);
}

// --------------------------------------------------------------------------------- tonemap

TEST(Tonemap, AcesIsMonotonicBoundedAndBlackStaysBlack) {
  EXPECT_EQ(tlTonemapAces(vec3(0.0f)).x, 0.0f);
  EXPECT_EQ(tlTonemapAces(vec3(-5.0f)).x, 0.0f);
  float prev = -1.0f;
  for (float x = 0.0f; x < 100.0f; x += 0.05f) {
    float y = tlTonemapAces(vec3(x)).y;
    EXPECT_GE(y, prev - 1e-6f) << x;
    EXPECT_LE(y, 1.0f);
    prev = y;
  }
  EXPECT_EQ(tlTonemapAces(vec3(1000.0f)).x, 1.0f);
  EXPECT_LT(tlTonemapAces(vec3(20.0f)).y, 1.0f);  // header: grey reaches 1 at about 25.7
  EXPECT_EQ(tlTonemapAces(vec3(30.0f)).y, 1.0f);
  // Mid grey lands in the middle of the display range.
  float mid = tlTonemapAces(vec3(0.18f)).y;
  EXPECT_GT(mid, 0.1f);
  EXPECT_LT(mid, 0.3f);
}

TEST(Tonemap, AcesMatricesAreHillsAndPreserveWhite) {
  // M * e_r is the first constructor triple, i.e. the first column: glm is column-major. GLSL
  // is too (checked by constant-folding the same literals with glslangValidator: M * (1,0,0)
  // folds to (0.59719, 0.076, 0.0284)). Hill's first ROW is (0.59719, 0.35458, 0.04823).
  expectVecNear(tlAcesInputMatrix() * vec3(1, 0, 0), vec3(0.59719f, 0.07600f, 0.02840f), 1e-6f);
  vec3 firstRow = glm::transpose(tlAcesInputMatrix())[0];
  expectVecNear(firstRow, vec3(0.59719f, 0.35458f, 0.04823f), 1e-6f);
  expectVecNear(tlAcesOutputMatrix() * vec3(0, 0, 1), vec3(-0.07367f, -0.00605f, 1.07602f), 1e-6f);
  // Each of Hill's rows sums to 1, so grey in is grey out; a transposed matrix would tint it.
  expectVecNear(tlAcesInputMatrix() * vec3(1.0f), vec3(1.0f), 1e-4f);
  expectVecNear(tlAcesOutputMatrix() * vec3(1.0f), vec3(1.0f), 1e-4f);
  for (float x : {0.01f, 0.18f, 1.0f, 4.0f}) {
    vec3 y = tlTonemapAces(vec3(x));
    EXPECT_NEAR(y.x, y.y, 1e-4f) << x;
    EXPECT_NEAR(y.z, y.y, 1e-4f) << x;
  }
}

TEST(Tonemap, NarkowiczMatchesItsClosedForm) {
  auto f = [](double x) { return std::min(1.0, x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)); };
  EXPECT_EQ(tlTonemapAcesNarkowicz(vec3(0.0f)).x, 0.0f);
  for (float x : {0.01f, 0.18f, 0.5f, 1.0f, 3.0f, 7.0f, 10.0f, 1e4f})
    EXPECT_NEAR(tlTonemapAcesNarkowicz(vec3(x)).x, f(x), 1e-6) << x;
  EXPECT_NEAR(tlTonemapAcesNarkowicz(vec3(1.0f)).x, 2.54f / 3.16f, 1e-6f);
  float prev = -1.0f;
  for (float x = 0.0f; x < 50.0f; x += 0.05f) {
    float y = tlTonemapAcesNarkowicz(vec3(x)).z;
    EXPECT_GE(y, prev - 1e-6f) << x;
    EXPECT_LE(y, 1.0f);
    prev = y;
  }
}

// --------------------------------------------------------------------------------- packing

TEST(Packing, OctahedralRoundTripIsAccurateEverywhere) {
  // Measured worst cases: float 1.5e-5 deg; 16-bit snorm with plain rounding (an RG16_SNORM
  // target) 0.0037 deg; the precise encoder 0.0025 deg.
  double worstFloat = 0.0, worstRounded = 0.0, worstPrecise = 0.0;
  auto check = [&](vec3 n) {
    n = normalize(n);
    vec2 e = tlOctEncode(n);
    EXPECT_LE(std::abs(e.x), 1.0f);
    EXPECT_LE(std::abs(e.y), 1.0f);
    EXPECT_NEAR(glm::length(tlOctDecode(e)), 1.0f, 1e-6f);
    vec2 q(std::round(e.x * 32767.0f) / 32767.0f, std::round(e.y * 32767.0f) / 32767.0f);
    worstFloat = std::max(worstFloat, angleDeg(n, tlOctDecode(e)));
    worstRounded = std::max(worstRounded, angleDeg(n, tlOctDecode(q)));
    worstPrecise = std::max(worstPrecise, angleDeg(n, tlOctDecodeSnorm16(tlOctEncodeSnorm16(n))));
  };
  for (vec3 n : {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                 vec3(1, 1, -1), vec3(-1, -1, -1), vec3(1e-6f, -1e-6f, -1), vec3(-1e-7f, 1e-7f, 1)})
    check(n);
  const int steps = 300;
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; j < 2 * steps; ++j) {
      double theta = kPiD * i / steps, phi = kPiD * j / steps;
      check(vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))));
    }
  for (vec3 n : randomUnitVectors(20000, 11)) check(n);
  EXPECT_LT(worstFloat, 0.001);
  EXPECT_LT(worstRounded, 0.01);
  EXPECT_LT(worstPrecise, 0.003);
  EXPECT_LE(worstPrecise, worstRounded);
}

TEST(Packing, OctahedralDecodeOfAnyPointIsUnit) {
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j)
      EXPECT_NEAR(glm::length(tlOctDecode(vec2(i / 20.0f, j / 20.0f))), 1.0f, 1e-6f);
}

TEST(Packing, Snorm2x16MatchesTheBuiltinBitForBit) {
  std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 0.5f, -0.5f, 1e-6f, -1e-6f};
  // Values whose scaled form sits exactly on or just either side of k + 0.5, where a naive
  // floor(s + 0.5) goes wrong.
  for (int k = 0; k < 32767; k += 97)
    for (float s : {float(k) + 0.5f, std::nextafter(float(k) + 0.5f, 0.0f), std::nextafter(float(k) + 0.5f, 1e9f)}) {
      values.push_back(s / 32767.0f);
      values.push_back(-s / 32767.0f);
    }
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  for (int i = 0; i < 20000; ++i) values.push_back(u(rng));
  for (size_t i = 0; i + 1 < values.size(); ++i) {
    vec2 v(values[i], values[i + 1]);
    ASSERT_EQ(tlPackSnorm2x16(v), glm::packSnorm2x16(v)) << v.x << " " << v.y;
  }
  EXPECT_EQ(tlPackSnorm2x16(vec2(1.0f, -1.0f)), 0x7FFFu | (0x8001u << 16));
}

TEST(Packing, UnpackSnorm2x16FollowsTheGlslSpecForEveryWord) {
  // GLSL: clamp(f / 32767.0, -1, 1) with f the signed 16-bit value. glm multiplies by the
  // reciprocal instead, so it can differ by one ulp.
  auto spec = [](uint bits) { return std::max(float(int16_t(uint16_t(bits))) / 32767.0f, -1.0f); };
  for (uint lo = 0; lo < 65536u; ++lo) {
    uint p = lo | ((65535u - lo) << 16);
    vec2 a = tlUnpackSnorm2x16(p), b = glm::unpackSnorm2x16(p);
    ASSERT_EQ(a.x, spec(lo)) << lo;
    ASSERT_EQ(a.y, spec(65535u - lo)) << lo;
    ASSERT_NEAR(a.x, b.x, 1.2e-7f) << lo;
    ASSERT_NEAR(a.y, b.y, 1.2e-7f) << lo;
    if (lo != 0x8000u) {
      ASSERT_EQ(tlPackSnorm2x16(a) & 0xFFFFu, lo) << lo;  // pack(unpack(w)) = w
    }
  }
  EXPECT_EQ(tlUnpackSnorm2x16(0x8000u).x, -1.0f);  // -32768 clamps like the builtin
}

TEST(Packing, HalfPairsRoundTrip) {
  for (vec2 v : {vec2(0.0f, 1.0f), vec2(-2.0f, 0.5f), vec2(65504.0f, -65504.0f), vec2(6.103515625e-05f, 0.099975586f)}) {
    vec2 r = tlUnpackHalf2x16(tlPackHalf2x16(v));
    EXPECT_EQ(r.x, v.x);
    EXPECT_EQ(r.y, v.y);
  }
  EXPECT_EQ(tlPackHalf2x16(vec2(1.0f, -2.0f)), 0x3C00u | (0xC000u << 16));
  vec2 r = tlUnpackHalf2x16(tlPackHalf2x16(vec2(0.1f, 1000.3f)));
  EXPECT_NEAR(r.x, 0.1f, 0.1f / 1024.0f);
  EXPECT_NEAR(r.y, 1000.3f, 1000.3f / 1024.0f);
}

// -------------------------------------------------------------------------------------- SH

TEST(Sh, MetroConstantsAreTheBasisTimesTheCosineLobeBands) {
  // pi * Y00 and (2 pi / 3) * Y1, to the 6 digits the talk quotes.
  EXPECT_NEAR(kShIrradianceL0, kPiD * kShY00, 5e-6);
  EXPECT_NEAR(kShIrradianceL1, 2.0 * kPiD / 3.0 * kShY1, 5e-6);
  EXPECT_NEAR(kShY00, 0.5 / std::sqrt(kPiD), 1e-6);
  EXPECT_NEAR(kShY1, std::sqrt(3.0) / (2.0 * std::sqrt(kPiD)), 1e-6);
  EXPECT_NEAR(kShIrradianceL0, std::sqrt(kPiD) / 2.0, 1e-6);
  EXPECT_NEAR(kShIrradianceL1, std::sqrt(kPiD / 3.0), 1e-6);
  EXPECT_NEAR(kShDirectionalityNorm, kShY00 / kShY1, 1e-6);
}

ShLumaCoCg projectFibonacci(int n, vec3 (*radiance)(vec3)) {
  ShLumaCoCg sh = tlShZero();
  for (vec3 d : fibonacciSphere(n)) sh = tlShAdd(sh, tlShProjectRadiance(d, radiance(d)));
  return tlShScale(sh, float(4.0 * kPiD / n));
}

TEST(Sh, UniformRadianceResolvesToPiTimesL) {
  const vec3 L(0.8f, 0.5f, 0.2f);
  ShLumaCoCg sh = projectFibonacci(4096, [](vec3) { return vec3(0.8f, 0.5f, 0.2f); });
  for (vec3 n : randomUnitVectors(200, 5)) {
    vec3 e = tlShResolveIrradiance(sh, n);
    vec3 want = float(kPiD) * L;
    EXPECT_NEAR(e.x, want.x, 0.01f * want.x);
    EXPECT_NEAR(e.y, want.y, 0.01f * want.y);
    EXPECT_NEAR(e.z, want.z, 0.01f * want.z);
    expectVecNear(tlShEvaluate(sh, n), L, 0.01f, "radiance");
  }
  EXPECT_LT(tlShDirectionality(sh), 0.01f);
}

TEST(Sh, LinearRadianceResolvesToItsExactIrradiance) {
  // L(w) = c (a + b.w) lies in the L1 space, so the resolve is exact:
  // E(n) = c (pi a + (2 pi / 3) b.n).
  auto radiance = [](vec3 w) { return vec3(1.0f, 0.6f, 0.3f) * (1.0f + dot(vec3(0.3f, -0.5f, 0.4f), w)); };
  ShLumaCoCg sh = projectFibonacci(8192, radiance);
  for (vec3 n : randomUnitVectors(200, 9)) {
    float s = float(kPiD) * 1.0f + float(2.0 * kPiD / 3.0) * dot(vec3(0.3f, -0.5f, 0.4f), n);
    vec3 want = vec3(1.0f, 0.6f, 0.3f) * s;
    expectVecNear(tlShResolveIrradiance(sh, n), want, 0.01f * s);
    expectVecNear(tlShEvaluate(sh, n), radiance(n), 0.01f);
  }
}

TEST(Sh, UniformUpperHemisphereIsExactAtZenithAndHorizon) {
  // A sky of radiance L over z > 0: E(+z) = pi L exactly and E(horizon) = pi L / 2 exactly,
  // and the L1 truncation happens to reproduce both.
  ShLumaCoCg sh = projectFibonacci(1 << 15, [](vec3 w) { return w.z > 0.0f ? vec3(2.0f) : vec3(0.0f); });
  EXPECT_NEAR(tlShResolveIrradiance(sh, vec3(0, 0, 1)).y, 2.0 * kPiD, 0.01 * 2.0 * kPiD);
  EXPECT_NEAR(tlShResolveIrradiance(sh, vec3(1, 0, 0)).y, kPiD, 0.01 * kPiD);
  EXPECT_NEAR(tlShResolveIrradiance(sh, vec3(0, 0, -1)).y, 0.0, 0.01);
  expectVecNear(tlShDominantDirection(sh, vec3(1, 0, 0)), vec3(0, 0, 1), 1e-3f);
  // |L1| / (sqrt 3 L0) = (Y1 pi) / (sqrt 3 Y00 2 pi) = 1/2.
  EXPECT_NEAR(tlShDirectionality(sh), 0.5f, 0.005f);
}

TEST(Sh, SingleDirectionResolvesToTheL1ClampedCosineLobe) {
  // One unit-weight sample of radiance c from d: Y(n) = Y_c (1/4 + n.d / 2), colour kept.
  const vec3 c(3.0f, 1.0f, 0.5f);
  for (vec3 d : randomUnitVectors(50, 13)) {
    ShLumaCoCg sh = tlShProjectRadiance(d, c);
    expectVecNear(tlShResolveIrradiance(sh, d), 0.75f * c, 1e-5f, "along d");
    expectVecNear(tlShResolveIrradiance(sh, -d), vec3(0.0f), 1e-6f, "against d");
    for (vec3 n : randomUnitVectors(20, 17)) {
      float k = std::max(0.25f + 0.5f * dot(n, d), 0.0f);
      expectVecNear(tlShResolveIrradiance(sh, n), k * c, 1e-5f);
      float r = std::max(kShY00 * kShY00 + kShY1 * kShY1 * dot(n, d), 0.0f);
      expectVecNear(tlShEvaluate(sh, n), r * c, 1e-5f);
    }
    expectVecNear(tlShDominantDirection(sh, vec3(0, 0, 1)), d, 1e-5f);
    EXPECT_NEAR(tlShDirectionality(sh), 1.0f, 1e-5f);
  }
}

TEST(Sh, IsLinearAndDegeneratesSafely) {
  ShLumaCoCg a = tlShProjectRadiance(vec3(0, 0, 1), vec3(1, 2, 3));
  ShLumaCoCg b = tlShProjectRadiance(vec3(1, 0, 0), vec3(0.5f, 0.1f, 0.0f));
  ShLumaCoCg sum = tlShAdd(tlShScale(a, 2.0f), b);
  ShLumaCoCg direct = tlShProjectRadiance(vec3(0, 0, 1), vec3(2, 4, 6));
  direct = tlShAdd(direct, b);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(sum.shY[i], direct.shY[i], 1e-6f);
  EXPECT_NEAR(sum.coCg.x, direct.coCg.x, 1e-6f);
  ShLumaCoCg half = tlShLerp(a, b, 0.5f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(half.shY[i], 0.5f * (a.shY[i] + b.shY[i]), 1e-6f);
  EXPECT_NEAR(half.coCg.y, 0.5f * (a.coCg.y + b.coCg.y), 1e-6f);

  ShLumaCoCg zero = tlShZero();
  expectVecNear(tlShResolveIrradiance(zero, vec3(0, 0, 1)), vec3(0.0f), 0.0f);
  expectVecNear(tlShEvaluate(zero, vec3(0, 0, 1)), vec3(0.0f), 0.0f);
  expectVecNear(tlShDominantDirection(zero, vec3(0, 1, 0)), vec3(0, 1, 0), 0.0f);
  EXPECT_EQ(tlShDirectionality(zero), 0.0f);
}

// A sample from a strong emitter stored in half floats. Saturating each channel on
// its own (what an RGBA16F store does) leaves a colour with a negative channel; fitting the
// whole SH keeps the colour (non-negative, same chroma ratio) and the direction.
TEST(Sh, FittingIntoHalfRangeKeepsTheColourWhereSaturatingDoesNot) {
  const vec3 dir = glm::normalize(vec3(0.3f, 0.8f, -0.5f));
  // 4 pi / 64: a uniform-sphere sample's Monte Carlo weight for 64 rays, of a green 1e7 emitter.
  const ShLumaCoCg sample = tlShScale(tlShProjectRadiance(dir, vec3(2e6f, 1e7f, 1.5e6f)), 4.0f * float(kPiD) / 64.0f);
  auto meanColour = [](const ShLumaCoCg& s) { return tlYCoCgToRgb(vec3(s.shY.x, s.coCg.x, s.coCg.y)); };
  auto saturate = [](ShLumaCoCg s) {
    for (int i = 0; i < 4; ++i) s.shY[i] = std::clamp(s.shY[i], -kShHalfMax, kShHalfMax);
    s.coCg = glm::clamp(s.coCg, vec2(-kShHalfMax), vec2(kShHalfMax));
    return s;
  };
  ASSERT_GT(sample.shY.x, kShHalfMax);  // the case: beyond the half range
  EXPECT_LT(std::min({meanColour(saturate(sample)).x, meanColour(saturate(sample)).z}), -1000.0f);  // the bug
  const ShLumaCoCg fitted = tlShFitHalf(sample);
  for (int i = 0; i < 4; ++i) EXPECT_LE(std::abs(fitted.shY[i]), kShHalfMax);
  const vec3 colour = meanColour(fitted);
  EXPECT_GE(std::min({colour.x, colour.y, colour.z}), 0.0f);
  EXPECT_NEAR(colour.x / colour.y, 0.2f, 1e-4f);  // the emitter's chroma
  EXPECT_LT(angleDeg(tlShDominantDirection(fitted, vec3(0, 1, 0)), dir), 1e-3);
  // In range: unchanged.
  const ShLumaCoCg small = tlShProjectRadiance(dir, vec3(1, 2, 3));
  EXPECT_EQ(tlShFitHalf(small).shY, small.shY);
  EXPECT_EQ(tlShFitHalf(small).coCg, small.coCg);
}

// -------------------------------------------------------------------------------- sampling

// A stratified grid of uniforms: deterministic and low-variance.
template <class F>
void forEachGridSample(int n, F f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) f(vec2((i + 0.5f) / n, (j + 0.5f) / n));
}

TEST(Sampling, CosineHemisphereHasMeanCosineTwoThirds) {
  double sumCos = 0.0, sumX = 0.0, sumY = 0.0, sumCos2 = 0.0;
  int count = 0;
  forEachGridSample(256, [&](vec2 u) {
    vec3 w = tlSampleCosineHemisphere(u);
    EXPECT_GE(w.z, 0.0f);
    EXPECT_NEAR(glm::length(w), 1.0f, 1e-5f);
    sumCos += w.z, sumCos2 += double(w.z) * w.z, sumX += w.x, sumY += w.y, ++count;
  });
  EXPECT_NEAR(sumCos / count, 2.0 / 3.0, 1e-3);
  EXPECT_NEAR(sumCos2 / count, 0.5, 1e-3);
  EXPECT_NEAR(sumX / count, 0.0, 1e-3);
  EXPECT_NEAR(sumY / count, 0.0, 1e-3);
  EXPECT_NEAR(tlCosineHemispherePdf(1.0f), 1.0 / kPiD, 1e-7);
  EXPECT_EQ(tlCosineHemispherePdf(-0.5f), 0.0f);
  // Random (hashed) uniforms too: the sampler must not depend on stratification.
  double s = 0.0;
  const int n = 1 << 16;
  for (int i = 0; i < n; ++i) s += tlSampleCosineHemisphere(tlRandom2(uvec3(uint(i), 1u, 2u))).z;
  EXPECT_NEAR(s / n, 2.0 / 3.0, 0.005);
}

TEST(Sampling, ConcentricDiskIsAreaUniform) {
  int inner = 0, count = 0;
  forEachGridSample(200, [&](vec2 u) {
    vec2 p = tlSampleConcentricDisk(u);
    EXPECT_LE(glm::length(p), 1.0f + 1e-6f);
    inner += glm::length(p) < 0.5f, ++count;
  });
  EXPECT_NEAR(double(inner) / count, 0.25, 0.005);
  EXPECT_EQ(glm::length(tlSampleConcentricDisk(vec2(0.5f))), 0.0f);
}

TEST(Sampling, UniformSphereAndHemisphereMoments) {
  double sz = 0.0, sz2 = 0.0, hz = 0.0;
  int count = 0;
  forEachGridSample(256, [&](vec2 u) {
    vec3 s = tlSampleUniformSphere(u), h = tlSampleUniformHemisphere(u);
    EXPECT_NEAR(glm::length(s), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(h), 1.0f, 1e-5f);
    EXPECT_GE(h.z, 0.0f);
    sz += s.z, sz2 += double(s.z) * s.z, hz += h.z, ++count;
  });
  EXPECT_NEAR(sz / count, 0.0, 1e-3);
  EXPECT_NEAR(sz2 / count, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(hz / count, 0.5, 1e-3);
  EXPECT_FLOAT_EQ(kUniformSpherePdf, float(1.0 / (4.0 * kPiD)));
  EXPECT_FLOAT_EQ(kUniformHemispherePdf, float(1.0 / (2.0 * kPiD)));
}

TEST(Sampling, BasisFromNormalIsRightHandedOrthonormal) {
  std::vector<vec3> normals = randomUnitVectors(5000, 21);
  for (vec3 n : {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, -1, 0), normalize(vec3(1e-4f, 0, -1)),
                 normalize(vec3(0, 1e-7f, -1)), normalize(vec3(1, 1, 1e-8f))})
    normals.push_back(n);
  for (vec3 n : normals) {
    mat3 m = tlBasisFromNormal(n);
    vec3 t = m[0], b = m[1];
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f);
    EXPECT_NEAR(dot(t, b), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(b, n), 0.0f, 1e-5f);
    expectVecNear(m[2], n, 0.0f);
    expectVecNear(cross(t, b), n, 1e-5f, "right-handed");
    expectVecNear(tlLocalToWorld(vec3(0, 0, 1), n), n, 1e-6f);
  }
}

TEST(Sampling, GgxDistributionIsNormalisedAndSampledByItsPdf) {
  for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f}) {
    // Integral of D(h) (n.h) over the hemisphere = 1: d(omega) = 2 pi d(cos theta).
    const int n = 20000;
    double sum = 0.0, inCone = 0.0;
    const double cosCone = std::cos(alpha * 0.8);  // a cone that holds part of the lobe
    for (int i = 0; i < n; ++i) {
      double ct = (i + 0.5) / n;
      double p = tlGgxHalfVectorPdf(float(ct), alpha) * 2.0 * kPiD / n;
      sum += p;
      if (ct > cosCone) inCone += p;
    }
    EXPECT_NEAR(sum, 1.0, 0.01) << alpha;
    // The sampler puts the same fraction of half vectors inside the cone.
    int hits = 0, count = 0;
    forEachGridSample(200, [&](vec2 u) {
      vec3 h = tlSampleGgxHalfVector(u, alpha);
      EXPECT_GE(h.z, 0.0f);
      EXPECT_NEAR(glm::length(h), 1.0f, 1e-5f);
      hits += h.z > cosCone, ++count;
    });
    EXPECT_NEAR(double(hits) / count, inCone, 0.01) << alpha;
  }
  // alpha = 1 makes D constant (1/pi), so half vectors are cosine distributed.
  double s = 0.0;
  int count = 0;
  forEachGridSample(200, [&](vec2 u) { s += tlSampleGgxHalfVector(u, 1.0f).z, ++count; });
  EXPECT_NEAR(s / count, 2.0 / 3.0, 1e-3);
  EXPECT_NEAR(tlGgxD(0.3f, 1.0f), 1.0 / kPiD, 1e-6);
}

TEST(Sampling, SmithG2MatchesHeitzClosedForm) {
  auto lambda = [](double c, double a) {
    double t2 = (1.0 - c * c) / (c * c);
    return 0.5 * (-1.0 + std::sqrt(1.0 + a * a * t2));
  };
  for (float alpha : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float nl : {0.05f, 0.3f, 0.8f, 1.0f})
      for (float nv : {0.1f, 0.5f, 1.0f}) {
        double want = 1.0 / (1.0 + lambda(nl, alpha) + lambda(nv, alpha));
        EXPECT_NEAR(tlSmithG2HeightCorrelated(nl, nv, alpha), want, 1e-5) << alpha << " " << nl << " " << nv;
      }
  EXPECT_EQ(tlSmithG2HeightCorrelated(0.0f, 0.5f, 0.3f), 0.0f);
  EXPECT_NEAR(tlSmithG2HeightCorrelated(1.0f, 1.0f, 0.5f), 1.0f, 1e-6f);
}

TEST(Sampling, LambertReflectsItsAlbedoAndSchlickHitsItsEnds) {
  // Integral of f cos over the hemisphere, by cosine-weighted sampling: f * pi.
  vec3 albedo(0.9f, 0.5f, 0.1f);
  double sum = 0.0;
  int count = 0;
  forEachGridSample(64, [&](vec2 u) {
    vec3 w = tlSampleCosineHemisphere(u);
    if (w.z > 0.0f) sum += tlLambertBrdf(albedo).y * w.z / tlCosineHemispherePdf(w.z);
    ++count;
  });
  EXPECT_NEAR(sum / count, 0.5, 1e-4);
  EXPECT_NEAR(tlFresnelSchlick(vec3(0.04f), 1.0f).x, 0.04f, 1e-6f);
  EXPECT_NEAR(tlFresnelSchlick(vec3(0.04f), 0.0f).x, 1.0f, 1e-6f);
  EXPECT_NEAR(tlFresnelSchlick(vec3(0.04f), 0.5f).x, 0.04f + 0.96f / 32.0f, 1e-6f);
}

// Chi-square statistic of n values in [0,1) over 16 bins.
template <class F>
double chiSquare16(int n, F value) {
  std::vector<int> bins(16, 0);
  for (int i = 0; i < n; ++i) {
    float v = value(i);
    EXPECT_GE(v, 0.0f);
    EXPECT_LT(v, 1.0f);
    ++bins[std::min(int(v * 16.0f), 15)];
  }
  double expected = n / 16.0, chi2 = 0.0;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  return chi2;
}

TEST(Sampling, HashesAreDeterministicAndLookUniform) {
  // Known answers from an independent (Python) transcription of Jarzynski & Olano's code.
  EXPECT_EQ(tlPcgHash(0u), 0x07bb2fe2u);
  EXPECT_EQ(tlPcgHash(1u), 0xa8beea3cu);
  EXPECT_EQ(tlPcgHash(12345u), 0xf45ead0eu);
  uvec3 h = tlPcg3d(uvec3(1u, 2u, 3u));
  EXPECT_EQ(h.x, 0xfa9f79a6u);
  EXPECT_EQ(h.y, 0x48f2f44cu);
  EXPECT_EQ(h.z, 0x596f5ab1u);

  EXPECT_EQ(tlUintToUnitFloat(0u), 0.0f);
  EXPECT_LT(tlUintToUnitFloat(0xFFFFFFFFu), 1.0f);
  EXPECT_EQ(tlUintToUnitFloat(0x80000000u), 0.5f);

  // 15 degrees of freedom: mean 15, P(chi2 > 37.7) = 0.001. Sequential inputs are the hard case.
  const int n = 160000;
  EXPECT_LT(chiSquare16(n, [](int i) { return tlUintToUnitFloat(tlPcgHash(uint(i))); }), 40.0);
  EXPECT_LT(chiSquare16(n, [](int i) { return tlUintToUnitFloat(tlPcg3d(uvec3(uint(i % 400), uint(i / 400), 0u)).x); }), 40.0);
  EXPECT_LT(chiSquare16(n, [](int i) { return tlUintToUnitFloat(tlPcg3d(uvec3(7u, 9u, uint(i))).z); }), 40.0);
  EXPECT_LT(chiSquare16(n, [](int i) { return tlRandom2(uvec3(uint(i % 400), uint(i / 400), 5u)).y; }), 40.0);
  // Neighbouring pixels decorrelate: adjacent values differ in their top bin about 15/16 of the time.
  int same = 0;
  for (int i = 0; i < 10000; ++i)
    same += int(tlUintToUnitFloat(tlPcgHash(uint(i))) * 16.0f) == int(tlUintToUnitFloat(tlPcgHash(uint(i + 1))) * 16.0f);
  EXPECT_NEAR(same / 10000.0, 1.0 / 16.0, 0.02);
}

// ---------------------------------------------------------------------------------- shading

// The BRDF's energy (albedo, compensation, environment terms) is tested in test_brdf.cpp.

TEST(Shading, MetalsHaveNoDiffuseAndF0IsBaseColour) {
  SurfaceParams s = tlSurface(vec3(1.0f, 0.78f, 0.34f), 0.25f, 1.0f);
  EXPECT_EQ(s.diffuse.x, 0.0f);
  EXPECT_NEAR(s.f0.y, 0.78f, 1e-6f);
  SurfaceParams d = tlSurface(vec3(0.5f), 0.5f, 0.0f);
  EXPECT_NEAR(d.f0.x, 0.04f, 1e-6f);
}

TEST(Shading, EnvironmentSpecularIsBoundedAndFinite) {
  for (float r : {0.0f, 0.25f, 0.5f, 1.0f})
    for (float nv : {0.0f, 1e-4f, 0.1f, 0.5f, 1.0f}) {
      vec3 e = tlEnvironmentSpecular(tlSurface(vec3(1.0f), r, 1.0f), nv);
      EXPECT_TRUE(std::isfinite(e.x));
      EXPECT_GE(e.x, 0.0f);
      // A white metal reflects all of a uniform sky (the multiple-scattering compensation).
      EXPECT_NEAR(e.x, 1.0f, 1e-5f);
    }
}

// ------------------------------------------------------------------------- specular from SH

// What the RT path accumulates under an open uniform sky of radiance L (shared/rt.h: cosine
// samples, each projected with the SH sample weight): the mean over a fine stratified grid.
ShLumaCoCg openSkySh(vec3 n, float L) {
  const int g = 256;
  ShLumaCoCg sum = tlShZero();
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      vec3 d = tlRtRayDirection(n, vec2((i + 0.5f) / g, (j + 0.5f) / g));
      sum = tlShAdd(sum, tlRtProjectSample(n, d, vec3(L)));
    }
  return tlShScale(sum, 1.0f / float(g * g));
}

// The open sky's directionality is the closed form kShOpenSkyDirectionality, and its
// specular is exactly L times the environment BRDF, at every roughness and angle (the
// composite's sky term, which this replaces: no jump at the far-field fade).
TEST(ShSpecular, OpenSkyGivesTheEnvironmentTerm) {
  const float L = 2.5f;
  const vec3 n(0, 0, 1);
  ShLumaCoCg sh = openSkySh(n, L);
  EXPECT_NEAR(tlShDirectionality(sh), kShOpenSkyDirectionality, 1e-3f);
  EXPECT_NEAR(tlShResolveIrradiance(sh, n).x, kPi * L, 1e-3f * kPi * L);
  for (float r : {0.1f, 0.5f, 1.0f})
    for (float nv : {0.15f, 0.5f, 1.0f}) {
      SurfaceParams s = tlSurface(vec3(1.0f, 0.78f, 0.34f), r, 1.0f);
      vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
      vec3 expected = L * tlEnvironmentSpecular(s, nv);
      vec3 got = tlShSpecular(sh, s, n, v, kShOpenSkyDirectionality);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 2e-3f * expected[c]) << r << " " << nv;
    }
}

// One sample from d (directionality 1) is a light from d giving the resolved irradiance on
// the surface, shaded with GGX at the material's own roughness: the highlight and nothing
// else. Seen away from the mirror direction it dims; from behind the surface it is 0.
TEST(ShSpecular, SingleDirectionIsAGgxLightAtTheMaterialsRoughness) {
  SurfaceParams s = tlSurface(vec3(0.9f), 0.3f, 1.0f);
  vec3 n(0, 0, 1), v = glm::normalize(vec3(0.6f, 0.0f, 0.8f));
  vec3 mirror = glm::reflect(-v, n);
  ShLumaCoCg sh = tlRtProjectSample(n, mirror, vec3(3.0f));
  EXPECT_NEAR(tlShDirectionality(sh), 1.0f, 1e-4f);
  EXPECT_NEAR(tlShExcessDirectionality(sh, kShOpenSkyDirectionality), 1.0f, 1e-3f);
  vec3 expected = tlBrdfSpecular(s, n, v, mirror) * tlShResolveIrradiance(sh, n).x;
  vec3 got = tlShSpecular(sh, s, n, v, kShOpenSkyDirectionality);
  EXPECT_NEAR(got.x, expected.x, 2e-3f * expected.x);
  EXPECT_LT(tlShSpecular(tlShProjectRadiance(v, vec3(3.0f)), s, n, v, kShOpenSkyDirectionality).x, 0.1f * got.x);
  EXPECT_NEAR(tlShSpecular(tlShProjectRadiance(vec3(0, 0, -1), vec3(3.0f)), s, n, v, kShOpenSkyDirectionality).x, 0.0f, 1e-6f);
}

// The open sky plus one bright direction: directionality between the two, the lobe rougher
// than the material; always finite, never negative, zero for no light, and a metal (no
// diffuse albedo) still reflects.
TEST(ShSpecular, MixedLightIsBoundedAndMetalsReflect) {
  SurfaceParams metal = tlSurface(vec3(1.0f, 0.78f, 0.34f), 0.2f, 1.0f);
  EXPECT_EQ(metal.diffuse.x, 0.0f);
  vec3 n(0, 0, 1);
  ShLumaCoCg mixed = tlShAdd(openSkySh(n, 1.0f), tlRtProjectSample(n, glm::normalize(vec3(0.3f, 0.0f, 1.0f)), vec3(2.0f)));
  const float a = tlShExcessDirectionality(mixed, kShOpenSkyDirectionality);
  EXPECT_GT(a, 0.1f);
  EXPECT_LT(a, 0.9f);
  EXPECT_GT(tlShSpecularAlpha(metal.alpha, a), metal.alpha);
  for (float nv : {1e-4f, 0.3f, 1.0f}) {
    vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
    vec3 e = tlShSpecular(mixed, metal, n, v, kShOpenSkyDirectionality);
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(e[c]));
      EXPECT_GE(e[c], 0.0f);
    }
    EXPECT_GT(e.x, 0.0f) << "a metal reflects indirect light";
  }
  EXPECT_EQ(tlShSpecular(tlShZero(), metal, n, n, kShOpenSkyDirectionality).x, 0.0f);
}

// Stochastic transparency's thresholds: every aligned 4x4 block holds (k + 0.5) / 16 once each,
// so BLEND keeps round(16 alpha) of every block's 16 pixels, and MASK and OPAQUE ignore xi.
TEST(AlphaModes, OrderedDitherKeepsAlphaOfEveryFourByFourBlock) {
  for (uint32_t bx = 0; bx < 3; ++bx)
    for (uint32_t by = 0; by < 3; ++by) {
      std::vector<float> values;
      for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) values.push_back(tlOrderedDither4(4 * bx + x, 4 * by + y));
      std::sort(values.begin(), values.end());
      for (int k = 0; k < 16; ++k) EXPECT_FLOAT_EQ(values[size_t(k)], (float(k) + 0.5f) / 16.0f) << bx << "," << by;
    }
  for (float alpha : {0.0f, 0.25f, 0.5f, 0.8125f, 1.0f}) {
    int kept = 0;
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x) kept += !tlMaterialCutout(kAlphaBlend, 0.5f, alpha, tlOrderedDither4(x + 8, y + 4));
    EXPECT_EQ(kept, int(std::lround(16.0f * alpha))) << "alpha " << alpha;
  }
  // Neighbours in a 2x2 block are far apart (a checkerboard at alpha 1/2), not a ramp.
  EXPECT_NEAR(std::fabs(tlOrderedDither4(0, 0) - tlOrderedDither4(1, 0)), 0.5f, 0.01f);
  EXPECT_TRUE(tlMaterialCutout(kAlphaMask, 0.5f, 0.49f, 0.99f));
  EXPECT_FALSE(tlMaterialCutout(kAlphaMask, 0.5f, 0.5f, 0.0f));
  EXPECT_FALSE(tlMaterialCutout(kAlphaOpaque, 0.5f, 0.0f, 0.9f));
  // The moving dither stays in (0, 1) and takes 8 different values at a pixel over 8 frames.
  std::vector<float> frames;
  for (uint32_t f = 0; f < 8; ++f) {
    frames.push_back(tlAlphaDither(3, 1, f, true));
    EXPECT_GT(frames.back(), 0.0f);
    EXPECT_LT(frames.back(), 1.0f);
    EXPECT_EQ(tlAlphaDither(3, 1, f, false), tlOrderedDither4(3, 1));
  }
  std::sort(frames.begin(), frames.end());
  EXPECT_EQ(std::adjacent_find(frames.begin(), frames.end()), frames.end());
}

}  // namespace
}  // namespace tl::shared
