// What `twinlight tune` searches and how it decides (session/tune_space.h, session/tune_front.h,
// session/tune.h): candidates from the schema, a seeded population, fronts that never drop a
// point on noise, and the choice under a budget.
#include "session/session.h"
#include "session/settings_json.h"
#include "session/tune.h"
#include "session/tune_front.h"
#include "session/tune_space.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace tl::session {
namespace {

using lighting::findSetting;

std::vector<double> candidatesOf(const char* name) { return candidateValues(*findSetting(name)); }

TEST(TuneSpace, CandidatesComeFromTheDefaultAndTheRange) {
  EXPECT_EQ(candidatesOf("rtDenoise"), (std::vector<double>{0, 1}));
  EXPECT_EQ(candidatesOf("rtCachePaths"), (std::vector<double>{1024, 2048, 4096, 8192, 16384}));
  // A range that starts at 0 offers it (the value that turns the lobe's rays off).
  EXPECT_EQ(candidatesOf("rtReflectionRoughness"), (std::vector<double>{0, 0.125, 0.25, 0.5, 1}));
  // The range clips the ladder: 1 and 2 are the checkerboard divisor's only values.
  EXPECT_EQ(candidatesOf("rtReflectionRoughDivisor"), (std::vector<double>{1, 2}));
  // A default of 0 climbs from 1.
  EXPECT_EQ(candidatesOf("rtDisocclusionRays"), (std::vector<double>{0, 1, 2, 4, 8}));
  // Powers of two stay so (legacyVoxelResolution 64 in 8..256).
  EXPECT_EQ(candidatesOf("legacyVoxelResolution"), (std::vector<double>{16, 32, 64, 128, 256}));
  for (const auto& s : lighting::settingsSchema())
    if (s.flags & lighting::kSettingTune) {
      for (double v : candidateValues(s)) EXPECT_FALSE(lighting::settingRangeError(s, v)) << s.name << " " << v;
    }
}

TEST(TuneSpace, APathSearchesItsOwnAndTheCommonSettingsButNoWindow) {
  std::set<std::string> rt;
  for (const TunableSetting& t : tunableSettings("rt")) {
    rt.insert(std::string(t.info->name));
    EXPECT_TRUE(t.info->owner == "rt" || t.info->owner == "common") << t.info->name;
    EXPECT_GE(t.candidates.size(), 2u) << t.info->name;
  }
  EXPECT_TRUE(rt.count("rtHalfResolution") && rt.count("shadowMapSize"));
  EXPECT_FALSE(rt.count("lightShadowMapSize"));  // rt traces its lights' shadows: it never builds those maps
  EXPECT_FALSE(rt.count("legacyConeDivisor"));
  EXPECT_FALSE(rt.count("rtMaxAccumFrames"));  // a still image cannot see a window's ghosts
  for (const TunableSetting& t : tunableSettings("reference")) EXPECT_EQ(t.info->owner, "common");  // none is the reference's
  // A feature is always searched, and its off value is one the schema takes.
  for (const auto& s : lighting::settingsSchema())
    if (s.flags & lighting::kSettingFeature) {
      EXPECT_TRUE(s.flags & lighting::kSettingTune) << s.name;
      EXPECT_FALSE(lighting::settingRangeError(s, featureOffValue(s))) << s.name;
    }
  EXPECT_EQ(featureOffValue(*findSetting("rtCacheMinGain")), 2.0);  // above 1: the cache never runs
  EXPECT_EQ(featureOffValue(*findSetting("rtReflectionRoughness")), 0.0);
}

TEST(TuneSpace, ThePopulationIsTheSameForASeedAndDistinct) {
  const auto space = tunableSettings("rt");
  const auto a = samplePopulation(space, 40, 7), b = samplePopulation(space, 40, 7), c = samplePopulation(space, 40, 8);
  ASSERT_EQ(a.size(), 40u);
  EXPECT_TRUE(a[0].overrides.empty());  // the defaults first
  std::set<std::string> distinct;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].overrides, b[i].overrides);
    EXPECT_EQ(a[i].name, fmt::format("c{:03}", i));
    distinct.insert(a[i].overrides.dump());
    // Every override is a candidate and applies through the schema's checks.
    EXPECT_NO_THROW(applySettingsJson(lighting::RenderSettings{}, a[i].overrides)) << a[i].overrides.dump();
    for (const auto& [name, value] : a[i].overrides.items()) {
      const auto* info = findSetting(name);
      ASSERT_NE(info, nullptr);
      const double stored = info->get(applySettingsJson(lighting::RenderSettings{}, {{name, value}}));
      const auto cands = candidateValues(*info);
      EXPECT_TRUE(std::count(cands.begin(), cands.end(), stored)) << name << " " << value;
      EXPECT_NE(stored, info->defaultValue) << name;
    }
  }
  EXPECT_EQ(distinct.size(), a.size());
  size_t differ = 0;
  for (size_t i = 1; i < a.size(); ++i) differ += a[i].overrides != c[i].overrides;
  EXPECT_GT(differ, 30u);
  // A space too small for the count gives what it has, once each.
  std::vector<TunableSetting> one{{findSetting("rtDenoise"), {0, 1}}};
  EXPECT_EQ(samplePopulation(one, 10, 1).size(), 2u);
}

TunePoint point(const std::string& name, double time, double spread, double error, double halfWidth) {
  TunePoint p;
  p.name = name;
  p.time = time, p.timeLow = time - spread, p.timeHigh = time + spread;
  p.frameMs = time * 10.0;
  p.error = {error, error, error - halfWidth, error + halfWidth};
  return p;
}

TEST(TuneFront, APointIsDroppedOnlyWhenSignificantlyBeaten) {
  const TunePoint a = point("a", 1.0, 0.05, 0.10, 0.01);
  // Slower and worse, both beyond the noise: dominated.
  EXPECT_TRUE(dominates(a, point("b", 1.5, 0.05, 0.20, 0.01)));
  // Slower beyond the noise, the error within it: still dominated (no better on either).
  EXPECT_TRUE(dominates(a, point("c", 1.5, 0.05, 0.105, 0.01)));
  // A little slower and a little worse, both within noise: kept.
  EXPECT_FALSE(dominates(a, point("d", 1.04, 0.05, 0.105, 0.01)));
  // Significantly more accurate though slower: kept, and it does not dominate a.
  const TunePoint e = point("e", 2.0, 0.05, 0.05, 0.01);
  EXPECT_FALSE(dominates(a, e));
  EXPECT_FALSE(dominates(e, a));
  const auto front = paretoFront({point("b", 1.5, 0.05, 0.20, 0.01), e, a, point("d", 1.04, 0.05, 0.105, 0.01)});
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0].name, "a");
  EXPECT_EQ(front[1].name, "d");
  EXPECT_EQ(front[2].name, "e");
}

TEST(TuneFront, SurvivorsPreferTheBudgetThenTheFrontThenTheError) {
  const std::vector<TunePoint> points{point("slow-best", 3.0, 0.01, 0.01, 0.001), point("fast-bad", 0.5, 0.01, 0.30, 0.001),
                                      point("mid", 0.9, 0.01, 0.10, 0.001), point("mid-worse", 0.95, 0.01, 0.12, 0.001),
                                      point("fast-good", 0.6, 0.01, 0.11, 0.001)};
  const auto kept = survivors(points, 3, 1.25);
  ASSERT_EQ(kept.size(), 3u);
  // Within the budget, the first front (mid, fast-good, fast-bad) by error; slow-best only if room.
  EXPECT_EQ(kept[0].name, "mid");
  EXPECT_EQ(kept[1].name, "fast-good");
  EXPECT_EQ(kept[2].name, "fast-bad");
  EXPECT_EQ(survivors(points, 5, 1.25).back().name, "slow-best");
  // The order of the input does not matter.
  std::vector<TunePoint> reversed(points.rbegin(), points.rend());
  const auto again = survivors(reversed, 3, 1.25);
  for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(again[i].name, kept[i].name);
}

TEST(TuneFront, TheChoiceIsTheCheapestWithinNoiseOfTheBest) {
  const std::vector<TunePoint> points{point("best", 0.95, 0.01, 0.100, 0.01), point("close-cheap", 0.7, 0.01, 0.105, 0.01),
                                      point("cheap-bad", 0.5, 0.01, 0.300, 0.01), point("over", 2.0, 0.01, 0.01, 0.001)};
  const auto chosen = chooseWithinBudget(points, 1.0);
  ASSERT_TRUE(chosen);
  EXPECT_EQ(chosen->name, "close-cheap");  // within noise of the best, cheaper
  EXPECT_EQ(chooseWithinBudget(points, 3.0)->name, "over");  // significantly better than all others
  EXPECT_FALSE(chooseWithinBudget(points, 0.4));
}

TEST(TuneFront, TheGuardKeepsTheChoiceFromSlidingIntoADarkerImage) {
  // Within noise of the best on relMSE (fewer fireflies because the bounced light is gone) but
  // significantly worse on FLIP, the guard: the cheaper, darker point is not chosen.
  TunePoint full = point("full", 1.0, 0.01, 0.10, 0.01), dark = point("dark", 0.6, 0.01, 0.105, 0.01);
  full.guard = metrics::NoiseAwareFigure{0.08, 0.08, 0.078, 0.082};
  dark.guard = metrics::NoiseAwareFigure{0.18, 0.18, 0.178, 0.182};
  EXPECT_TRUE(significantlyMoreAccurate(full, dark));
  EXPECT_FALSE(significantlyMoreAccurate(dark, full));
  EXPECT_TRUE(dominates(full, dark) == false);  // dark is significantly faster: both stay on the front
  EXPECT_EQ(chooseWithinBudget({full, dark}, 1.5)->name, "full");
  // The most accurate point by the error may be the one full of fireflies: the guard is taken
  // against the best guard among the close points, not against it.
  TunePoint spiky = point("spiky", 1.4, 0.01, 0.098, 0.01);
  spiky.guard = metrics::NoiseAwareFigure{4.99, 4.99, 3.8, 6.1};
  EXPECT_EQ(chooseWithinBudget({full, dark, spiky}, 1.5)->name, "full");
  // Without the guard the cheaper point within noise wins.
  full.guard.reset(), dark.guard.reset();
  EXPECT_EQ(chooseWithinBudget({full, dark}, 1.5)->name, "dark");
}

TEST(TuneBudget, TakesARatioToTheBaselineOrMilliseconds) {
  EXPECT_DOUBLE_EQ(parseTuneBudget("1.3x-legacy", "legacy").ratio, 1.3);
  EXPECT_DOUBLE_EQ(parseTuneBudget("25ms", "legacy").ms, 25.0);
  EXPECT_THROW(parseTuneBudget("1.3x-rt", "legacy"), SessionError);  // times are the baseline's
  EXPECT_THROW(parseTuneBudget("fast", "legacy"), SessionError);
  EXPECT_THROW(parseTuneBudget("0x-legacy", "legacy"), SessionError);
  EXPECT_THROW(parseTuneBudget("-1ms", "legacy"), SessionError);
}

}  // namespace
}  // namespace tl::session
