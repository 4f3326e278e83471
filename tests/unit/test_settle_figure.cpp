// The doctor's ghosting figure (session/doctor.h settleFigure): how many frames a sequence of
// images takes to settle within its own noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "session/doctor.h"

namespace tl::session {
namespace {

// 64 pixels of value 1 with a deterministic +-noise pattern, plus a ghost of `ghost` on the
// first half of the pixels.
std::vector<double> frame(double ghost, double noise, int seed) {
  std::vector<double> v(64);
  for (size_t i = 0; i < v.size(); ++i) {
    const double sign = ((i * 7 + size_t(seed) * 13) % 5) < 2 ? 1.0 : -1.0;
    v[i] = 1.0 + noise * sign + (i < 32 ? ghost : 0.0);
  }
  return v;
}

TEST(SettleFigure, CountsTheFramesAGhostStaysAboveTheNoise) {
  // A ghost of 0.8 falling to a quarter each frame: 0.8, 0.2, 0.05, 0.0125, ... The residual of
  // a ghost g over half the image is g / 2 against a settled image of about 1 (0.40, 0.10, 0.026,
  // 0.007 with the noise); the noise floor is 0.002, so the threshold is 2 * 0.002 + 0.01 = 0.014:
  // the first three frames stand out, the fourth does not.
  std::vector<std::vector<double>> frames;
  for (int k = 0; k < 16; ++k) frames.push_back(frame(0.8 * std::pow(0.25, k), 0.002, k));
  const auto fig = settleFigure(frames);
  ASSERT_TRUE(fig);
  EXPECT_EQ(fig->lag, 3u);
  EXPECT_TRUE(fig->settled);
  EXPECT_NEAR(fig->firstResidual, 0.4, 0.03);
  EXPECT_GT(fig->noiseFloor, 0.0);
  EXPECT_LT(fig->noiseFloor, 0.005);
}

TEST(SettleFigure, NoiseAloneSettlesAtOnce) {
  std::vector<std::vector<double>> frames;
  for (int k = 0; k < 12; ++k) frames.push_back(frame(0.0, 0.05, k));
  const auto fig = settleFigure(frames);
  ASSERT_TRUE(fig);
  EXPECT_EQ(fig->lag, 0u) << "noise as large as the tail's is not a ghost";
}

TEST(SettleFigure, AGhostThatNeverFadesLastsTheWholeHold) {
  // Half the image stays wrong until the last four frames: every frame before them stands out.
  std::vector<std::vector<double>> frames;
  for (int k = 0; k < 10; ++k) frames.push_back(frame(k < 6 ? 0.5 : 0.0, 0.0, k));
  const auto fig = settleFigure(frames);
  ASSERT_TRUE(fig);
  EXPECT_EQ(fig->lag, 6u);
  EXPECT_FALSE(fig->settled) << "every frame before the tail stood out";
}

TEST(SettleFigure, TooFewFramesOrNoLightGiveNothing) {
  EXPECT_FALSE(settleFigure({frame(0.0, 0.0, 0), frame(0.0, 0.0, 1)}));
  EXPECT_FALSE(settleFigure(std::vector<std::vector<double>>(8, std::vector<double>(16, 0.0))));
  EXPECT_FALSE(settleFigure({}));
}

}  // namespace
}  // namespace tl::session
