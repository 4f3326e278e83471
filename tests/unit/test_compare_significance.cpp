// compare's rankings and regression gate on figures with intervals (session/compare_significance.h):
// two paths are ranked only where their intervals part, and a gate neither passes nor fails on a
// figure whose interval holds its threshold.
#include "session/compare_significance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tl::session {
namespace {

nlohmann::json figure(double value, double low, double high) {
  return {{"value", value}, {"raw", value}, {"low", low}, {"high", high}};
}

// A path's entry as runCompare writes it: the plain figure and its significance.
nlohmann::json path(const std::string& name, double value, double low, double high) {
  nlohmann::json sig;
  for (const std::string& m : significanceMetrics()) sig[m] = figure(value, low, high);
  return {{"path", name}, {"relMSE", value}, {"relMSE_norm", value}, {"RMSE", value}, {"significance", sig}};
}

TEST(CompareSignificance, RanksOnlyWherePathsIntervalsPart) {
  const nlohmann::json results = {path("legacy", 0.20, 0.18, 0.22), path("rt", 0.10, 0.08, 0.12),
                                  path("direct", 0.21, 0.19, 0.23)};
  const nlohmann::json rankings = rankPaths(results);
  EXPECT_EQ(rankings["relMSE"]["order"], "rt < legacy ~ direct");
  int withinNoise = 0;
  for (const auto& p : rankings["relMSE_norm"]["pairs"]) withinNoise += p["verdict"] == "within noise";
  EXPECT_EQ(withinNoise, 1);
}

TEST(CompareSignificance, GateNeitherPassesNorFailsOnTheReferencesNoise) {
  const std::vector<GateThreshold> limit = {{"relMSE_norm", 0.15}};
  // Wholly below, holding the threshold, wholly above.
  const nlohmann::json below = evaluateGate(nlohmann::json::array({path("rt", 0.10, 0.08, 0.12)}), limit);
  EXPECT_TRUE(below["passed"].get<bool>());
  EXPECT_TRUE(below["decided"].get<bool>());
  const nlohmann::json holds = evaluateGate(nlohmann::json::array({path("rt", 0.14, 0.12, 0.16)}), limit);
  EXPECT_FALSE(holds["passed"].get<bool>()) << "a figure within noise of its threshold does not pass";
  EXPECT_FALSE(holds["decided"].get<bool>());
  EXPECT_TRUE(holds["failures"].empty()) << "nor does it fail";
  ASSERT_EQ(holds["withinNoise"].size(), 1u);
  EXPECT_EQ(holds["withinNoise"][0]["path"], "rt");
  // (Its value alone, 0.14, would have passed it.)
  const nlohmann::json above = evaluateGate(nlohmann::json::array({path("rt", 0.20, 0.17, 0.23)}), limit);
  EXPECT_FALSE(above["passed"].get<bool>());
  EXPECT_TRUE(above["decided"].get<bool>());
  EXPECT_EQ(above["failures"].size(), 1u);
  // A failure decides the gate whatever else is within noise.
  const nlohmann::json both =
      evaluateGate(nlohmann::json::array({path("rt", 0.14, 0.12, 0.16), path("legacy", 0.20, 0.17, 0.23)}), limit);
  EXPECT_TRUE(both["decided"].get<bool>());
  EXPECT_EQ(both["failures"].size(), 1u);
  // A figure without an interval (RMSE; or another renderer's reference) fails above its threshold.
  const nlohmann::json plain = evaluateGate(nlohmann::json::array({path("rt", 0.14, 0.12, 0.16)}), {{"RMSE", 0.1}});
  EXPECT_EQ(plain["failures"].size(), 1u);
  EXPECT_TRUE(plain["withinNoise"].empty());
}

TEST(CompareSignificance, SeveralFramesAverageAndTheirSpreadWidensTheInterval) {
  auto frame = [](double v) {
    nlohmann::json f = nlohmann::json::object();
    for (const std::string& m : significanceMetrics()) f[m] = {{"value", v}, {"raw", v + 0.001}, {"low", v - 0.01}, {"high", v + 0.02}};
    return f;
  };
  // One frame is what it was.
  EXPECT_EQ(combineFrameSignificance({frame(0.1)}), frame(0.1));
  // Alike frames: the mean, the frames' own interval.
  const nlohmann::json same = combineFrameSignificance({frame(0.1), frame(0.1), frame(0.1), frame(0.1)});
  EXPECT_NEAR(same["relMSE_norm"]["value"].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(same["relMSE_norm"]["low"].get<double>(), 0.09, 1e-12);
  EXPECT_NEAR(same["relMSE_norm"]["high"].get<double>(), 0.12, 1e-12);
  EXPECT_EQ(same["relMSE_norm"]["frames"].get<size_t>(), 4u);
  // A firefly in one frame of four: the mean moves, and the interval widens by Student's t
  // (3 degrees of freedom: 3.182) over the standard error of the mean, in quadrature.
  const nlohmann::json spiky = combineFrameSignificance({frame(0.1), frame(0.1), frame(0.1), frame(0.5)});
  const auto& f = spiky["FLIP_norm"];
  EXPECT_NEAR(f["value"].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(f["raw"].get<double>(), 0.201, 1e-12);
  EXPECT_NEAR(f["frameSpread"].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(f["high"].get<double>(), 0.2 + std::hypot(0.02, 3.182 * 0.2 / 2.0), 1e-9);
  EXPECT_NEAR(f["low"].get<double>(), 0.2 - std::hypot(0.01, 3.182 * 0.2 / 2.0), 1e-9);
}

}  // namespace
}  // namespace tl::session
