// The RT path's CPU-testable pieces against closed forms: the one-uint hit record over the
// whole distance range, RGB9E5, the SH sample weight (unbiased irradiance at the sampling
// normal), the blue-noise masks, the simplifier and instance culling.
#include "lighting/legacy/legacy_path.h"
#include "lighting/rt/blue_noise.h"
#include "lighting/common/scene_accel.h"
#include "shared/rt.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tl {
namespace {

using namespace shared;

TEST(RtHitRecord, DistanceRoundTripsWithinHalfPrecisionOverTheWholeRange) {
  double worstRelative = 0.0, worstTiny = 0.0;
  for (double d = 1e-7; d <= 65504.0; d *= 1.0007) {
    uint32_t rec = tlRtPackHit(float(d), vec3(0.5f));
    ASSERT_TRUE(tlRtIsHit(rec)) << d;
    double back = tlRtHitDistance(rec);
    if (d >= 6.104e-5) worstRelative = std::max(worstRelative, std::abs(back - d) / d);
    else worstTiny = std::max(worstTiny, std::abs(back - d));
  }
  EXPECT_LE(worstRelative, std::ldexp(1.0, -11) * 1.0001);  // round to nearest half
  EXPECT_LE(worstTiny, std::ldexp(1.0, -25) * 1.0001);
  // Beyond the range: clamped, still a hit, never a code.
  EXPECT_EQ(tlRtHitDistance(tlRtPackHit(1e9f, vec3(0.0f))), 65504.0f);
  EXPECT_TRUE(tlRtIsHit(tlRtPackHit(1e9f, vec3(1.0f))));
  EXPECT_EQ(tlRtHitDistance(tlRtPackHit(-3.0f, vec3(0.0f))), 0.0f);
}

TEST(RtHitRecord, CodesAreNeverDistances) {
  EXPECT_TRUE(tlRtIsMiss(kRtHitMiss));
  EXPECT_FALSE(tlRtIsHit(kRtHitMiss));
  EXPECT_TRUE(tlRtIsPending(kRtHitPending));
  EXPECT_FALSE(tlRtIsHit(kRtHitPending));
  EXPECT_FALSE(tlRtIsMiss(kRtHitPending));
  // Every finite distance and albedo stays clear of both codes.
  for (float d : {0.0f, 1e-30f, 1.0f, 65504.0f, std::numeric_limits<float>::infinity()})
    for (float a : {0.0f, 0.5f, 1.0f}) {
      uint32_t rec = tlRtPackHit(d, vec3(a));
      EXPECT_TRUE(tlRtIsHit(rec)) << d << " " << a;
    }
}

TEST(RtHitRecord, AlbedoRoundTripsWithinTheDocumentedBound) {
  for (int r = 0; r <= 100; ++r)
    for (int g = 0; g <= 100; g += 7) {
      vec3 a(r / 100.0f, g / 100.0f, 1.0f - r / 100.0f);
      vec3 back = tlRtHitAlbedo(tlRtPackHit(2.0f, a));
      EXPECT_LE(std::abs(back.x - a.x), std::sqrt(a.x) / 31.0f + 1.0f / 961.0f);
      EXPECT_LE(std::abs(back.y - a.y), std::sqrt(a.y) / 63.0f + 1.0f / 3969.0f);
      EXPECT_LE(std::abs(back.z - a.z), std::sqrt(a.z) / 31.0f + 1.0f / 961.0f);
    }
  EXPECT_EQ(tlRtHitAlbedo(tlRtPackHit(1.0f, vec3(0.0f))), vec3(0.0f));
  EXPECT_EQ(tlRtHitAlbedo(tlRtPackHit(1.0f, vec3(1.0f))), vec3(1.0f));
}

TEST(RtHitRecord, MetalsBounceTheirSpecularColour) {
  vec3 gold(1.0f, 0.78f, 0.34f);
  vec3 metal = tlRtHitAlbedoFromMaterial(gold, 1.0f);
  EXPECT_NEAR(metal.x, 1.0f, 1e-6f);  // diffuse 0: albedo (1 - F0) + F0 = F0 = base
  EXPECT_NEAR(metal.z, 0.34f, 1e-6f);
  vec3 white = tlRtHitAlbedoFromMaterial(vec3(0.8f), 0.0f);
  EXPECT_NEAR(white.x, 0.8f * 0.96f + 0.04f, 1e-6f);
}

TEST(Rgb9e5, RoundTripsWithSharedExponentPrecision) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> e(-12.0f, 15.0f);
  for (int i = 0; i < 20000; ++i) {
    vec3 c(std::exp2(e(rng)), std::exp2(e(rng)), std::exp2(e(rng)));
    vec3 back = tlUnpackRgb9e5(tlPackRgb9e5(c));
    float m = std::max({c.x, c.y, c.z});
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(back[k] - c[k]), m / 256.0f) << c.x << " " << c.y << " " << c.z;
  }
  EXPECT_EQ(tlPackRgb9e5(vec3(0.0f)), 0u);
  EXPECT_EQ(tlUnpackRgb9e5(0u), vec3(0.0f));
  vec3 big = tlUnpackRgb9e5(tlPackRgb9e5(vec3(1e9f, 0.0f, -5.0f)));
  EXPECT_NEAR(big.x, 65408.0f, 1.0f);
  EXPECT_EQ(big.z, 0.0f);
}

// Mean of weighted cosine samples resolved at the sampling normal = irradiance, for any
// radiance distribution (here: uniform, a cosine lobe, and a tilted one-sided one).
TEST(RtShSampleWeight, ResolvesToTheIrradianceAtTheSamplingNormal) {
  const vec3 n = normalize(vec3(0.3f, 0.8f, -0.2f));
  auto check = [&](auto radiance, double exact) {
    ShLumaCoCg sum = tlShZero();
    const int k = 256;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        vec2 u((i + 0.5f) / k, (j + 0.5f) / k);
        vec3 d = tlRtRayDirection(n, u);
        sum = tlShAdd(sum, tlRtProjectSample(n, d, vec3(radiance(d))));
      }
    sum = tlShScale(sum, 1.0f / float(k * k));
    EXPECT_NEAR(tlShResolveIrradiance(sum, n).y, exact, 2e-3 * exact);
  };
  check([](vec3) { return 1.0f; }, kPi);                                    // uniform: pi L
  check([&](vec3 d) { return std::max(dot(d, n), 0.0f); }, 2.0 * kPi / 3.0);  // cosine lobe: 2 pi / 3
  const vec3 t = normalize(vec3(1.0f, 0.0f, 0.0f));
  // Light only from the half-space x > 0: irradiance by quadrature of the same integrand.
  double e = 0.0;
  const int q = 1024;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) {
      vec3 d = tlRtRayDirection(n, vec2((i + 0.5f) / q, (j + 0.5f) / q));
      e += dot(d, t) > 0.0f ? 1.0 : 0.0;
    }
  check([&](vec3 d) { return dot(d, t) > 0.0f ? 1.0f : 0.0f; }, kPi * e / (double(q) * q));
}

TEST(RtShSampleWeight, StaysBounded) {
  EXPECT_NEAR(tlRtShSampleWeight(1.0f), 4.0f * kPi / 3.0f, 1e-5f);
  EXPECT_NEAR(tlRtShSampleWeight(0.0f), 4.0f * kPi, 1e-5f);
}

TEST(BlueNoise, IsAPermutationWithoutLowFrequencyClumps) {
  const uint32_t n = 64;
  auto ranks = lighting::voidAndClusterRanks(n, 1);
  std::vector<uint16_t> sorted = ranks;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < n * n; ++i) ASSERT_EQ(sorted[i], i);
  EXPECT_EQ(ranks, lighting::voidAndClusterRanks(n, 1)) << "deterministic";
  // Variance of 4x4 block means: white noise gives var(U)/16; blue noise far less.
  auto blockVariance = [&](const std::vector<uint16_t>& r) {
    double sum = 0.0, sum2 = 0.0;
    int blocks = 0;
    for (uint32_t by = 0; by < n; by += 4)
      for (uint32_t bx = 0; bx < n; bx += 4) {
        double m = 0.0;
        for (uint32_t y = 0; y < 4; ++y)
          for (uint32_t x = 0; x < 4; ++x) m += (r[(by + y) * n + bx + x] + 0.5) / (n * n);
        m /= 16.0;
        sum += m, sum2 += m * m, ++blocks;
      }
    return sum2 / blocks - (sum / blocks) * (sum / blocks);
  };
  std::vector<uint16_t> white(n * n);
  for (uint32_t i = 0; i < n * n; ++i) white[i] = uint16_t(i);
  std::shuffle(white.begin(), white.end(), std::mt19937(3));
  double blue = blockVariance(ranks), whiteV = blockVariance(white);
  EXPECT_LT(blue, 0.25 * whiteV) << "blue " << blue << " white " << whiteV;
}

TEST(RtSimplify, ReducesAFineGridAndKeepsItsShape) {
  // A flat 64x64 grid: planar, so the simplifier may drop almost everything at no error.
  std::vector<scene::Vertex> v;
  std::vector<uint32_t> idx;
  const int g = 64;
  for (int y = 0; y <= g; ++y)
    for (int x = 0; x <= g; ++x) v.push_back({glm::vec3(x / float(g), 0.0f, y / float(g))});
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) {
      uint32_t a = y * (g + 1) + x, b = a + 1, c = a + g + 1, d = c + 1;
      idx.insert(idx.end(), {a, c, b, b, c, d});
    }
  float deviation = -1.0f;
  auto reduced = lighting::simplifyForRayTracing(v, idx, 0.25f, 0.01f, &deviation);
  EXPECT_LE(reduced.size(), idx.size() / 4);
  EXPECT_GT(reduced.size(), 0u);
  EXPECT_LE(deviation, 1e-4f);
  auto full = lighting::simplifyForRayTracing(v, idx, 1.0f, 0.01f, &deviation);
  EXPECT_EQ(full.size(), idx.size());
  EXPECT_EQ(deviation, 0.0f);
}

TEST(RtCulling, KeepsTheExpandedFrustumAndDropsTinyFarInstances) {
  // Camera at the origin looking down -z, 90 degree vertical field of view, square.
  glm::mat4 proj(0.0f);
  proj[0][0] = 1.0f;
  proj[1][1] = -1.0f;
  proj[2][3] = -1.0f;
  proj[3][2] = 0.1f;
  lighting::RtCulling c;
  c.viewProj = proj;
  c.margin = 1.0f;
  c.minAngle = 0.01f;
  std::vector<glm::vec3> centres = {{0, 0, -5},      // in view
                                    {0, 0, 5},       // behind, far from the frustum
                                    {0, 0, 0.5f},    // behind but within the margin
                                    {0, 0, -1000},   // in view but tiny: radius 1 at 1000 m
                                    {0, 0, -50},     // in view, radius 1 at 50 m: kept
                                    {20, 0, -5}};    // far to the side
  std::vector<float> radii = {0.5f, 0.5f, 0.2f, 1.0f, 1.0f, 0.5f};
  auto kept = lighting::cullInstances(centres, radii, c);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<uint32_t>{0, 2, 4}));
  // Distance culling (the blend distance plus the margin): the nearest point decides.
  c.maxDistance = 40.0f;
  kept = lighting::cullInstances(centres, radii, c);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<uint32_t>{0, 2}));
  c.maxDistance = 49.0f;  // instance 4's sphere reaches 49 m
  kept = lighting::cullInstances(centres, radii, c);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<uint32_t>{0, 2, 4}));
}

}  // namespace
}  // namespace tl

namespace tl {
namespace {

scene::Bounds box(glm::dvec3 lo, glm::dvec3 hi) {
  scene::Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(LegacyClipmap, TheAutomaticFinestLevelHoldsTheSceneAtAnyScale) {
  // Unset (0), the finest level holds the whole scene: one level, whatever its size in metres,
  // so the same scene at any scale gets the same voxels relative to itself.
  for (double scale : {0.01, 1.0, 100.0}) {
    auto cornell = lighting::fitLegacyClipmap(box(glm::dvec3(-1, 0, -1) * scale, glm::dvec3(1, 2, 1) * scale),
                                              glm::dvec3(0, 1, 3.9) * scale, 64, 0.0f, 4);
    EXPECT_EQ(cornell.clipmap.levels, 1u) << scale;
    EXPECT_EQ(cornell.clipmap.resolution, 64u);
    EXPECT_EQ(cornell.clipmap.mipCount, 6u);  // 32, 16, 8, 4, 2, 1
    // The level spans the scene: its minimum corner is at or below the scene's, camera-relative.
    EXPECT_LE(cornell.clipmap.levelMin[0].x, -1.0f * scale);
    EXPECT_LE(cornell.clipmap.levelMin[0].z, (-1.0f - 3.9f) * scale);
    EXPECT_NEAR(cornell.clipmap.levelMin[0].w, 2.0 * 1.02 / 64.0 * scale, 1e-6 * scale);  // the largest side, +2%, / R
    // The scene's central planes (x = 0, z = 0 here) lie inside voxels, not on their faces,
    // and its walls inside the level.
    const double voxel = cornell.clipmap.levelMin[0].w;
    for (int a : {0, 2}) {
      const double camera = a == 0 ? 0.0 : 3.9 * scale;
      const double centreInVoxels = (0.0 - camera - double(cornell.clipmap.levelMin[0][a])) / voxel;
      EXPECT_NEAR(centreInVoxels - std::floor(centreInVoxels), 0.5, 0.05) << scale << " axis " << a;
      EXPECT_GE(double(cornell.clipmap.levelMin[0][a]) + 64.0 * voxel, 1.0 * scale - camera) << scale << " axis " << a;
    }
  }
  auto atrium = lighting::fitLegacyClipmap(box({-12.5, -0.2, -12.5}, {12.5, 6, 12.5}), {0, 3.5, 13}, 64, 0.0f, 4);
  EXPECT_EQ(atrium.clipmap.levels, 1u);
  // A finest level set smaller: coarser ones double it until the scene is covered, at most maxLevels.
  auto finer = lighting::fitLegacyClipmap(box({-12.5, -0.2, -12.5}, {12.5, 6, 12.5}), {0, 3.5, 13}, 64, 16.0f, 4);
  EXPECT_EQ(finer.clipmap.levels, 2u);
  EXPECT_FLOAT_EQ(finer.clipmap.levelMin[1].w, 2.0f * finer.clipmap.levelMin[0].w);
  auto capped = lighting::fitLegacyClipmap(box({-500, 0, -500}, {500, 10, 500}), {0, 1, 0}, 64, 16.0f, 3);
  EXPECT_EQ(capped.clipmap.levels, 3u) << "at most maxLevels";
  EXPECT_EQ(lighting::fitLegacyClipmap(box({-1, 0, -1}, {1, 2, 1}), {}, 100, 0.0f, 4).clipmap.resolution, 128u)
      << "rounded up to a power of two";
}

TEST(LegacyClipmap, AFinerLevelFollowsTheCameraOnTheVoxelGridAndStaysInTheScene) {
  const auto bounds = box({-100, 0, -100}, {100, 10, 100});
  auto a = lighting::fitLegacyClipmap(bounds, {10.0, 1.0, 20.0}, 64, 16.0f, 4);
  const float voxel = a.clipmap.levelMin[0].w;
  EXPECT_FLOAT_EQ(voxel, 0.25f);
  // World minimum corner of level 0 lies half a voxel off the voxel grid (world-origin planes
  // fall inside voxels, not on their faces), around the camera.
  const double worldX = double(a.clipmap.levelMin[0].x) + 10.0;
  EXPECT_NEAR(worldX / voxel - 0.5, std::round(worldX / voxel - 0.5), 1e-3);
  EXPECT_LT(worldX, 10.0);
  EXPECT_GT(worldX + 16.0, 10.0);
  // Near the scene's edge the level is clamped into the bounds (one voxel of margin).
  auto edge = lighting::fitLegacyClipmap(bounds, {99.0, 1.0, 0.0}, 64, 16.0f, 4);
  EXPECT_LE(double(edge.clipmap.levelMin[0].x) + 99.0 + 16.0, 100.0 + voxel + 1e-3);
}

}  // namespace
}  // namespace tl

namespace tl::shared {
namespace {

// Screen radiance reused at a hit takes the hit record's albedo: same albedo, same light;
// twice the albedo, twice the reflected part; emission unchanged.
TEST(RtScreenRadiance, RecolouringScalesOnlyTheReflectedLight) {
  const glm::vec3 seen(0.9f, 0.5f, 0.3f), emission(0.1f, 0.1f, 0.1f), albedo(0.5f, 0.4f, 0.2f);
  glm::vec3 same = tlRtRecolourScreenRadiance(seen, emission, albedo, albedo);
  EXPECT_NEAR(same.r, seen.r, 1e-6f);
  EXPECT_NEAR(same.b, seen.b, 1e-6f);
  glm::vec3 twice = tlRtRecolourScreenRadiance(seen, emission, albedo, albedo * 2.0f);
  EXPECT_NEAR(twice.g, 0.1f + 2.0f * 0.4f, 1e-6f);
  glm::vec3 green = tlRtRecolourScreenRadiance(seen, glm::vec3(0.0f), glm::vec3(0.8f, 0.1f, 0.1f), glm::vec3(0.1f, 0.8f, 0.1f));
  EXPECT_LT(green.r, seen.r);
  EXPECT_GT(green.g, seen.g);
  // The darkest F0-rule albedo bounds the ratio.
  glm::vec3 dark = tlRtRecolourScreenRadiance(glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_NEAR(dark.r, 25.0f, 1e-4f);
}

TEST(Sampling, RadicalInverseMirrorsTheBits) {
  EXPECT_EQ(tlRadicalInverse2(0u), 0.0f);
  EXPECT_EQ(tlRadicalInverse2(1u), 0.5f);
  EXPECT_EQ(tlRadicalInverse2(2u), 0.25f);
  EXPECT_EQ(tlRadicalInverse2(3u), 0.75f);
  EXPECT_EQ(tlRadicalInverse2(5u), 0.625f);
  // The first 2^k points fill the 2^k strata of [0, 1) once each.
  std::vector<int> strata(64, 0);
  for (uint32_t i = 0; i < 64; ++i) ++strata[size_t(tlRadicalInverse2(i) * 64.0f)];
  EXPECT_TRUE(std::all_of(strata.begin(), strata.end(), [](int c) { return c == 1; }));
}

// Disocclusion rays: 16 rotated Hammersley directions estimate the irradiance of a uniform sky
// lit only above a horizon a third of the way up a tilted normal's hemisphere far better than
// 16 independent random rays do on average: what makes 16 rays a cell worth many frames.
TEST(RtDisocclusion, StratifiedRaysEstimateIrradianceClosely) {
  const vec3 n = normalize(vec3(0.9f, -0.2f, 0.35f));  // a third of its hemisphere below the horizon
  const vec3 up = vec3(0.0f, 0.0f, 1.0f);
  auto irradiance = [&](auto uniforms) {
    ShLumaCoCg sum = tlShZero();
    for (uint32_t i = 0; i < 16; ++i) {
      vec3 d = tlRtRayDirection(n, uniforms(i));
      float radiance = dot(d, up) > 0.0f ? 1.0f : 0.0f;  // sky above the horizon only
      sum = tlShAdd(sum, tlRtProjectSample(n, d, vec3(radiance)));
    }
    return tlShResolveLuma(tlShScale(sum, 1.0f / 16.0f), n);
  };
  // Closed form: the cosine-weighted share of the hemisphere above the horizon plane z = 0,
  // for a normal tilted by theta from up: E = pi (1 + cos theta) / 2.
  const double exact = kPi * (1.0 + n.z) / 2.0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  double stratifiedSq = 0.0, randomSq = 0.0;
  const int trials = 400;
  for (int t = 0; t < trials; ++t) {
    const vec2 rotation(uni(rng), uni(rng));
    const double s = irradiance([&](uint32_t i) { return tlRtDisocclusionUniforms(i, 16u, rotation); });
    const double r = irradiance([&](uint32_t) { return vec2(uni(rng), uni(rng)); });
    stratifiedSq += (s - exact) * (s - exact);
    randomSq += (r - exact) * (r - exact);
  }
  const double stratifiedRms = std::sqrt(stratifiedSq / trials) / exact, randomRms = std::sqrt(randomSq / trials) / exact;
  EXPECT_LT(stratifiedRms, 0.1) << "random rays: " << randomRms;
  EXPECT_LT(stratifiedRms, 0.5 * randomRms);
  RecordProperty("stratified_rms", std::to_string(stratifiedRms));
  RecordProperty("random_rms", std::to_string(randomRms));
}

// The SH weight for a sample of inverse pdf 1/p resolves to L cos / pdf; for the cosine pdf it
// is the usual one (the emitter samples' weight: tests/unit/test_emitter_table.cpp).
TEST(RtSh, WeightForAPdfIsTheCosineWeightAtTheCosinePdf) {
  EXPECT_NEAR(tlRtShWeightForPdf(0.6f, kPi / 0.6f), tlRtShSampleWeight(0.6f), 1e-5);
}

}  // namespace
}  // namespace tl::shared
