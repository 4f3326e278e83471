// The BLAS refit throttle: the 16 highest priorities plus 4 random others, priorities that
// grow with visibility and size and start over when refitted, nothing starving, and the
// vertex budget.
#include "lighting/common/blas_refit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace tl::lighting {
namespace {

std::vector<RefitCandidate> candidates(uint32_t n, uint32_t visibleBelow) {
  std::vector<RefitCandidate> c(n);
  for (uint32_t i = 0; i < n; ++i) c[i] = {i, 100, i < visibleBelow, i < visibleBelow ? 0.01f * float(i) : 0.0f};
  return c;
}

TEST(BlasRefit, SixteenHighestAndFourRandomOthers) {
  RefitScheduler s;
  auto stale = candidates(48, 24);
  auto chosen = s.choose(stale, RefitPolicy{}, 1);
  ASSERT_EQ(chosen.size(), 20u);
  // The first 16 are the largest visible meshes (23 down to 8).
  for (uint32_t k = 0; k < 16; ++k) EXPECT_EQ(chosen[k], 23u - k);
  for (uint32_t k = 16; k < 20; ++k) EXPECT_EQ(std::count(chosen.begin(), chosen.begin() + 16, chosen[k]), 0);
  for (uint32_t m : chosen) EXPECT_EQ(s.priority(m), 0.0f);
  const std::set<uint32_t> taken(chosen.begin(), chosen.end());
  for (uint32_t m = 0; m < 48; ++m) {
    if (taken.count(m)) continue;
    // What one frame gave it: visible ones 1 + 16 x their size, hidden ones 0.1.
    EXPECT_FLOAT_EQ(s.priority(m), m < 24 ? 1.0f + 16.0f * 0.01f * float(m) : 0.1f) << m;
  }
  EXPECT_EQ(s.choose(stale, RefitPolicy{}, 1).size(), 20u);
}

TEST(BlasRefit, EveryStaleMeshIsRefittedWithinAFewFrames) {
  RefitScheduler s;
  auto stale = candidates(48, 24);
  std::vector<int> lastRefit(48, -1), longestWait(48, 0);
  for (int frame = 0; frame < 200; ++frame) {
    for (uint32_t m : s.choose(stale, RefitPolicy{}, uint64_t(frame))) {
      longestWait[m] = std::max(longestWait[m], frame - lastRefit[m]);
      lastRefit[m] = frame;
    }
  }
  for (uint32_t m = 0; m < 48; ++m) {
    EXPECT_GE(lastRefit[m], 150) << "mesh " << m << " starved";
    EXPECT_LE(longestWait[m], 40) << "mesh " << m;
  }
  // Visible meshes wait less than invisible ones.
  int visibleWorst = *std::max_element(longestWait.begin(), longestWait.begin() + 24);
  int hiddenWorst = *std::max_element(longestWait.begin() + 24, longestWait.end());
  EXPECT_LT(visibleWorst, hiddenWorst);
}

TEST(BlasRefit, VertexBudgetLimitsAFrameButTheFirstPickAlwaysGoes) {
  RefitScheduler s;
  auto stale = candidates(10, 10);
  RefitPolicy p;
  p.vertexBudget = 350;  // three meshes of 100
  EXPECT_EQ(s.choose(stale, p, 0).size(), 3u);
  stale[9].vertices = 10000;
  p.vertexBudget = 50;
  auto one = s.choose(stale, p, 1);
  ASSERT_EQ(one.size(), 1u) << "over budget alone, still refitted";
}

TEST(BlasRefit, TheRandomDrawRepeatsForTheSameFrame) {
  auto stale = candidates(48, 0);
  RefitScheduler a, b;
  EXPECT_EQ(a.choose(stale, RefitPolicy{}, 7), b.choose(stale, RefitPolicy{}, 7));
}

}  // namespace
}  // namespace tl::lighting
