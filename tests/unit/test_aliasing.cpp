// planAliasing: resources alive at the same time never share bytes; resources whose
// lifetimes do not overlap do; alignment is respected; the plan is deterministic.
#include "graph/graph.h"

#include <gtest/gtest.h>

#include <random>

namespace tl::graph {
namespace {

bool overlapsInTime(const AliasRequest& a, const AliasRequest& b) { return a.firstPass <= b.lastPass && b.firstPass <= a.lastPass; }

void expectValid(const std::vector<AliasRequest>& req, const AliasPlan& plan) {
  ASSERT_EQ(plan.offsets.size(), req.size());
  for (size_t i = 0; i < req.size(); ++i) {
    EXPECT_EQ(plan.offsets[i] % req[i].alignment, 0u) << i;
    EXPECT_LE(plan.offsets[i] + req[i].size, plan.totalSize);
    for (size_t j = i + 1; j < req.size(); ++j) {
      if (!overlapsInTime(req[i], req[j])) continue;
      bool apart = plan.offsets[i] + req[i].size <= plan.offsets[j] || plan.offsets[j] + req[j].size <= plan.offsets[i];
      EXPECT_TRUE(apart) << "requests " << i << " and " << j << " are alive together and share bytes";
    }
  }
}

TEST(Aliasing, DisjointLifetimesShareMemory) {
  std::vector<AliasRequest> req{{1000, 256, 0, 1}, {1000, 256, 2, 3}, {500, 256, 4, 5}};
  AliasPlan plan = planAliasing(req);
  expectValid(req, plan);
  EXPECT_EQ(plan.unaliasedSize, 2500u);
  EXPECT_EQ(plan.totalSize, 1000u);
}

TEST(Aliasing, OverlappingLifetimesNeverShare) {
  std::vector<AliasRequest> req{{1000, 256, 0, 2}, {1000, 256, 1, 3}};
  AliasPlan plan = planAliasing(req);
  expectValid(req, plan);
  EXPECT_GE(plan.totalSize, 2000u);
}

TEST(Aliasing, RespectsAlignment) {
  std::vector<AliasRequest> req{{100, 1, 0, 5}, {100, 4096, 0, 5}, {10, 64, 0, 5}};
  AliasPlan plan = planAliasing(req);
  expectValid(req, plan);
}

TEST(Aliasing, RandomFramesAreValidAndDeterministic) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<AliasRequest> req;
    int n = 1 + int(rng() % 24);
    for (int i = 0; i < n; ++i) {
      uint32_t a = rng() % 12, b = rng() % 12;
      VkDeviceSize align = VkDeviceSize(1) << (rng() % 13);
      req.push_back({VkDeviceSize(1 + rng() % 100000), align, std::min(a, b), std::max(a, b)});
    }
    AliasPlan p1 = planAliasing(req), p2 = planAliasing(req);
    expectValid(req, p1);
    EXPECT_EQ(p1.offsets, p2.offsets);
    EXPECT_LE(p1.totalSize, p1.unaliasedSize + VkDeviceSize(n) * 4096);
  }
}

TEST(Aliasing, EmptyAndZeroSized) {
  EXPECT_EQ(planAliasing({}).totalSize, 0u);
  AliasPlan p = planAliasing({{0, 1, 0, 0}});
  EXPECT_EQ(p.totalSize, 0u);
}

}  // namespace
}  // namespace tl::graph
