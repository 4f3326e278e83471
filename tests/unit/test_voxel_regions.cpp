// The legacy clipmap's partial-update regions against hand-worked cases: the sun-shadow
// sweep of a changed box, its voxels in a level, merging, and mip footprints.
#include "lighting/legacy/voxel_regions.h"

#include <gtest/gtest.h>

namespace tl {
namespace {

using lighting::VoxelRegion;

scene::Bounds box(glm::dvec3 lo, glm::dvec3 hi) { return scene::Bounds{lo, hi}; }

// One level of 16 voxels of 0.5 m whose camera-relative corner is at -4 m, camera at (1, 0, 0).
shared::LegacyClipmap oneLevel() {
  shared::LegacyClipmap c{};
  c.levelMin[0] = glm::vec4(-4.0f, -4.0f, -4.0f, 0.5f);
  c.resolution = 16;
  c.levels = 1;
  c.mipCount = 4;
  return c;
}

TEST(VoxelRegions, AChangedBoxReachesDownItsShadowToTheGround) {
  const auto scene = box({-10, 0, -10}, {10, 5, 10});
  const auto b = box({0, 2, 0}, {1, 3, 1});
  // Sun straight down: the box's column down to y = 0.
  auto down = lighting::shadowSweptBounds(b, {0, -1, 0}, scene, 0.0);
  EXPECT_EQ(down.min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(down.max, glm::dvec3(1, 3, 1));
  // 45 degrees along +x: the shadow of the box's top lands 3 m further in x.
  auto slanted = lighting::shadowSweptBounds(b, glm::normalize(glm::dvec3(1, -1, 0)), scene, 0.0);
  EXPECT_NEAR(slanted.min.y, 0.0, 1e-9);
  EXPECT_NEAR(slanted.max.x, 4.0, 1e-9);
  EXPECT_NEAR(slanted.min.x, 0.0, 1e-9);
  // A margin grows it, but the sweep stays inside the scene.
  auto grown = lighting::shadowSweptBounds(b, {0, -1, 0}, scene, 0.25);
  EXPECT_EQ(grown.min, glm::dvec3(-0.25, 0, -0.25));
  EXPECT_EQ(grown.max, glm::dvec3(1.25, 3.25, 1.25));
}

TEST(VoxelRegions, ABoxCoversItsVoxelsAndOneMoreAroundClampedToTheLevel) {
  const auto c = oneLevel();
  const glm::dvec3 camera{1, 0, 0};  // the level spans [-3, 5) x [-4, 4)^2 in the world
  // x in [0, 1): voxels 6, 7 (+1 margin: 5..8); y, z in [0, 1): voxels 8, 9 (+1: 7..10).
  VoxelRegion r = lighting::voxelRegionOf(c, 0, camera, box({0, 0, 0}, {0.9, 0.9, 0.9}));
  EXPECT_EQ(r.min, glm::ivec3(5, 7, 7));
  EXPECT_EQ(r.max, glm::ivec3(9, 11, 11));
  EXPECT_EQ(r.voxels(), 4 * 4 * 4);
  auto world = lighting::worldBoundsOf(c, 0, camera, r);
  EXPECT_EQ(world.min, glm::dvec3(-0.5, -0.5, -0.5));
  EXPECT_EQ(world.max, glm::dvec3(1.5, 1.5, 1.5));
  EXPECT_EQ(lighting::voxelRegionOf(c, 0, camera, box({-100, -1, -1}, {100, 1, 1})).max.x, 16) << "clamped";
  EXPECT_TRUE(lighting::voxelRegionOf(c, 0, camera, box({10, 0, 0}, {11, 1, 1})).empty()) << "outside the level";
  EXPECT_TRUE(lighting::voxelRegionOf(c, 1, camera, box({0, 0, 0}, {1, 1, 1})).empty()) << "no such level";
}

TEST(VoxelRegions, OverlappingRegionsMergeDistantOnesStayApart) {
  const VoxelRegion a{{0, 0, 0}, {4, 4, 4}}, b{{2, 2, 2}, {6, 6, 6}}, far{{40, 40, 40}, {44, 44, 44}};
  auto merged = lighting::mergeVoxelRegions({a, far, b, VoxelRegion{}});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0], (VoxelRegion{{0, 0, 0}, {6, 6, 6}}));
  EXPECT_EQ(merged[1], far);
  // A union that reaches a third region takes it in too.
  auto chain = lighting::mergeVoxelRegions({{{0, 0, 0}, {4, 4, 4}}, {{10, 0, 0}, {14, 4, 4}}, {{3, 0, 0}, {11, 4, 4}}});
  ASSERT_EQ(chain.size(), 1u);
  EXPECT_EQ(chain[0], (VoxelRegion{{0, 0, 0}, {14, 4, 4}}));
  // Side by side: one region costs nothing more than two.
  auto touching = lighting::mergeVoxelRegions({{{0, 0, 0}, {4, 4, 4}}, {{4, 0, 0}, {8, 4, 4}}});
  EXPECT_EQ(touching.size(), 1u);
}

TEST(VoxelRegions, MipFootprintHoldsEveryTexelWhoseChildrenChanged) {
  const VoxelRegion r{{3, 4, 0}, {9, 5, 16}};
  EXPECT_EQ(lighting::mipFootprint(r, 1), (VoxelRegion{{1, 2, 0}, {5, 3, 8}}));
  EXPECT_EQ(lighting::mipFootprint(r, 2), (VoxelRegion{{0, 1, 0}, {3, 2, 4}}));
  EXPECT_EQ(lighting::mipFootprint(r, 4), (VoxelRegion{{0, 0, 0}, {1, 1, 1}}));
}

}  // namespace
}  // namespace tl
