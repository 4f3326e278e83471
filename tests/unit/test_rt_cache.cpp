// The radiance cache's pure parts (shared/rt_cache.h, lighting/rt/radiance_cache.h): cells,
// fixed point, the history blend and the measured switch.
#include "lighting/rt/radiance_cache.h"
#include "shared/rt_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>

using namespace tl::shared;
using tl::lighting::countCacheOutcomes;
using tl::lighting::RtCacheOutcomes;
using tl::lighting::RtCacheSwitch;

TEST(RtCache, LevelGrowsWithDistance) {
  EXPECT_EQ(tlRtCacheLevel(0.0f, 0.01f, 0.02f), 0u);
  EXPECT_EQ(tlRtCacheLevel(0.5f, 0.01f, 0.02f), 0u);  // 0.01 m covers 0.02 * 0.5
  EXPECT_EQ(tlRtCacheLevel(1.0f, 0.01f, 0.02f), 1u);  // 0.02 m: needs 0.02
  EXPECT_EQ(tlRtCacheLevel(3.0f, 0.01f, 0.02f), 3u);  // 0.06 m: 0.08
  for (float d : {0.1f, 1.0f, 7.3f, 100.0f, 5000.0f}) {
    const uint32_t l = tlRtCacheLevel(d, 0.01f, 0.02f);
    EXPECT_GE(0.01f * std::exp2(float(l)) * 1.0001f, 0.02f * d) << d;             // big enough
    if (l > 0) {
      EXPECT_LT(0.01f * std::exp2(float(l - 1)), 0.02f * d * 1.0001f) << d;  // the smallest such
    }
  }
  EXPECT_EQ(tlRtCacheLevel(1e30f, 0.01f, 0.02f), kRtCacheMaxLevel);
}

TEST(RtCache, TwoSidesOfAWallAreTwoCells) {
  const vec3 p(1.234f, 0.5f, -2.0f);
  const uvec2 front = tlRtCacheCell(p, vec3(0, 0, 1), 3.0f, 0.01f, 0.02f);
  const uvec2 back = tlRtCacheCell(p, vec3(0, 0, -1), 3.0f, 0.01f, 0.02f);
  const uvec2 floor = tlRtCacheCell(p, vec3(0, 1, 0), 3.0f, 0.01f, 0.02f);
  EXPECT_NE(front.y, back.y);
  EXPECT_NE(front.y, floor.y);
  // The same cell from a point nearby (cells at 3 m are 0.08 m).
  EXPECT_EQ(tlRtCacheCell(p + vec3(0.001f, 0.0f, 0.0f), vec3(0, 0.3f, 1), 3.0f, 0.01f, 0.02f), front);
}

// The coarse cell a hit falls back to: kRtCacheCoarseLevels levels up, so 4^2 cells of the
// same facing share it (cells at 3 m are 0.08 m: coarse ones 0.32 m); never the fine cell.
TEST(RtCache, CoarseCellHoldsItsNeighbours) {
  std::set<std::pair<uint32_t, uint32_t>> fine, coarse;
  for (int x = 0; x < 4; ++x)
    for (int z = 0; z < 4; ++z) {
      const vec3 p = vec3(0.32f * 3.0f + 0.08f * (float(x) + 0.5f), 0.5f, 0.32f * 2.0f + 0.08f * (float(z) + 0.5f));
      const uvec2 f = tlRtCacheCell(p, vec3(0, 1, 0), 3.0f, 0.01f, 0.02f);
      const uvec2 c = tlRtCacheCoarseCell(p, vec3(0, 1, 0), 3.0f, 0.01f, 0.02f);
      EXPECT_EQ(c, tlRtCacheCellAtLevel(p, vec3(0, 1, 0), 3u + kRtCacheCoarseLevels, 0.01f));
      EXPECT_NE(c.y, f.y);
      fine.insert({f.x, f.y});
      coarse.insert({c.x, c.y});
    }
  EXPECT_EQ(fine.size(), 16u);
  EXPECT_EQ(coarse.size(), 1u);
  // The other side of the wall is another coarse cell.
  EXPECT_NE(tlRtCacheCoarseCell(vec3(1.0f, 0.5f, 0.7f), vec3(0, -1, 0), 3.0f, 0.01f, 0.02f).y,
            tlRtCacheCoarseCell(vec3(1.0f, 0.5f, 0.7f), vec3(0, 1, 0), 3.0f, 0.01f, 0.02f).y);
}

TEST(RtCache, KeysRarelyCollide) {
  std::set<uint32_t> keys;
  int n = 0;
  for (int x = -20; x < 20; ++x)
    for (int y = -20; y < 20; ++y)
      for (int z = -5; z < 5; ++z, ++n) {
        const vec3 p = (vec3(float(x), float(y), float(z)) + 0.5f) * 0.08f;
        const uvec2 c = tlRtCacheCell(p, vec3(0, 1, 0), 3.0f, 0.01f, 0.02f);
        EXPECT_NE(c.y, 0u);
        keys.insert(c.y);
      }
  EXPECT_GE(keys.size(), size_t(n - 2));  // 16000 cells: a 32-bit key collides about never
}

TEST(RtCache, FixedPointIsUnbiased) {
  // Stochastic rounding keeps a value far below one unit in the mean.
  const float bound = 100.0f, value = 3.3e-5f * bound / kRtCacheFixedOne * 1e4f;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) sum += tlRtCacheFromFixed(tlRtCacheToFixed(value, bound, u(rng)), bound);
  EXPECT_NEAR(sum / n, value, 0.02 * value);
  EXPECT_EQ(tlRtCacheToFixed(2.0f * bound, bound, 0.0f), uint32_t(kRtCacheFixedOne));  // clamped
  EXPECT_EQ(tlRtCacheToFixed(-1.0f, bound, 0.5f), 0u);
  // The cap of samples a frame keeps a sum within 32 bits.
  EXPECT_LT(double(kRtCacheSampleCap) * (kRtCacheFixedOne + 1.0), 4294967296.0);
}

TEST(RtCache, BlendIsARunningMeanThenBounded) {
  vec4 h(0.0f);
  for (int i = 1; i <= 4; ++i) h = tlRtCacheBlend(h, vec3(float(i)), 1.0f, 64.0f, 1.0f);
  EXPECT_NEAR(h.x, 2.5f, 1e-6f);  // without fading: the mean of 1..4
  EXPECT_EQ(h.w, 4.0f);
  // Light switched off: with a history of at most 16 samples, 16 new samples a frame, the old
  // light halves every frame: below 1% in 7 frames.
  h = vec4(1.0f, 1.0f, 1.0f, 16.0f);
  for (int f = 0; f < 7; ++f) h = tlRtCacheBlend(h, vec3(0.0f), 16.0f, 16.0f, 1.0f);
  EXPECT_LT(h.x, 0.01f);
  // No samples: the value stays, its weight fades.
  const vec4 kept = tlRtCacheBlend(h, vec3(5.0f), 0.0f, 16.0f, 0.875f);
  EXPECT_EQ(kept.x, h.x);
  EXPECT_FLOAT_EQ(kept.w, h.w * 0.875f);
  // One sample a frame with fading 1 - 1/8: the weight settles at 8 samples (a window of 8
  // frames), so a cold start's dark samples weigh (7/8)^k after k frames.
  h = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  for (int f = 0; f < 40; ++f) h = tlRtCacheBlend(h, vec3(1.0f), 1.0f, 64.0f, 0.875f);
  EXPECT_NEAR(h.w, 8.0f, 0.05f);
  EXPECT_NEAR(h.x, 1.0f, 0.01f);
}

TEST(RtCache, OutcomesAndSwitch) {
  const RtCacheOutcome records[] = {{kRtCacheOutcomeNone, 5.0f, 5.0f, 0u},  // no path: nothing counts
                                    {kRtCacheOutcomeSky, 1.0f, 0.0f, 0u},
                                    {kRtCacheOutcomeOffScreen, 0.5f, 0.25f, 0u},
                                    {kRtCacheOutcomeOnScreen, 2.0f, 0.0f, 0u},
                                    {kRtCacheOutcomeOffScreen, 0.5f, std::nanf(""), 0u}};  // a bad value is dropped
  std::vector<uint8_t> bytes(sizeof records);
  std::memcpy(bytes.data(), records, sizeof records);
  const RtCacheOutcomes o = countCacheOutcomes(bytes);
  EXPECT_EQ(o.paths, 4u);
  EXPECT_EQ(o.offScreen, 2u);
  EXPECT_DOUBLE_EQ(o.offScreenShare(), 0.5);
  EXPECT_DOUBLE_EQ(o.gathered, 4.0);
  EXPECT_DOUBLE_EQ(o.added, 0.25);
  EXPECT_DOUBLE_EQ(o.addedShare(), 0.25 / 4.25);

  // The switch follows the light the cache adds, not how many rays end off screen.
  RtCacheSwitch sw;
  EXPECT_FALSE(sw.on());  // nothing measured yet: the probe paths measure first
  const auto measured = [](double gathered, double added) {
    RtCacheOutcomes m{100, 10, 40, 50};
    m.gathered = gathered, m.added = added;
    return m;
  };
  EXPECT_FALSE(sw.update(measured(100.0, 0.5), 0.02f));  // many rays off screen, little light added: off
  EXPECT_FALSE(sw.update(measured(100.0, 1.5), 0.02f));  // 1.5%: below the threshold, stays off
  EXPECT_TRUE(sw.update(measured(100.0, 25.0), 0.02f));  // a fifth of the light: on
  EXPECT_TRUE(sw.update(measured(100.0, 1.5), 0.02f));   // above half the threshold: stays on
  EXPECT_FALSE(sw.update(measured(100.0, 0.5), 0.02f));  // below half: off
  EXPECT_FALSE(sw.update(RtCacheOutcomes{}, 0.02f));     // nothing seen: kept
  // Rays whose length runs out inside the scene bring back only what the cache holds.
  RtCacheOutcomes shortRays{100, 0, 50, 10};
  shortRays.ended = 40;
  shortRays.gathered = 100.0;
  EXPECT_DOUBLE_EQ(shortRays.cacheGain(), 0.4);
  EXPECT_TRUE(sw.update(shortRays, 0.02f));
}
