// One acceleration structure for every tracer (lighting/common/scene_accel.h): switching a
// scene through every path that traces rays (rt, the reference, both plugins) and back builds
// each mesh's bottom level once per level of detail (the rt path's simplified one, the
// reference's full one) and never again; a tracer that built its own would add a set.
#include "lighting_checks.h"

#include "gpu/acceleration_structure.h"

#include <fmt/format.h>

namespace tl::test {
namespace {

class SceneAccelTest : public RayTracingTest {};

TEST_F(SceneAccelTest, EveryTracerBorrowsTheSceneStructuresBuiltOnce) {
  auto& s = session();
  // A new scene (a new id): nothing built for it yet, whatever earlier tests rendered.
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 24);
  const size_t meshes = s.scene().meshes.size();
  ASSERT_GT(meshes, 1u);

  const gpu::AccelerationStructureTotals start = gpu::accelerationStructureTotals();
  std::vector<std::string> steps;
  auto step = [&](const char* path) {
    const gpu::AccelerationStructureTotals before = gpu::accelerationStructureTotals();
    s.setPath(path);
    s.renderFrames(2);
    const gpu::AccelerationStructureTotals after = gpu::accelerationStructureTotals();
    const uint64_t built = after.bottomLevelBuilds - before.bottomLevelBuilds;
    steps.push_back(fmt::format("{}: {} bottom levels built in {:.1f} ms, {} top-level builds, {} bytes of "
                                "structures alive", path, built, after.bottomLevelBuildMs - before.bottomLevelBuildMs,
                                after.topLevelBuilds - before.topLevelBuilds, after.liveBytes));
    RecordProperty(fmt::format("{}_{}", steps.size(), path), steps.back());
    return built;
  };
  EXPECT_EQ(step("rt"), meshes) << "the simplified level: one bottom level per mesh";
  EXPECT_EQ(step("reference"), meshes) << "the full level: one bottom level per mesh";
  EXPECT_EQ(step("bentsky"), 0u) << "the plugin borrows the simplified level";
  EXPECT_EQ(step("ao"), 0u) << "the plugin borrows the simplified level";
  EXPECT_EQ(step("rt"), 0u) << "back to rt: nothing rebuilt";
  EXPECT_EQ(step("reference"), 0u) << "back to the reference: nothing rebuilt";
  const gpu::AccelerationStructureTotals end = gpu::accelerationStructureTotals();
  EXPECT_EQ(end.bottomLevelBuilds - start.bottomLevelBuilds, 2 * meshes) << "two levels, each built once";
  for (const auto& line : steps) std::printf("  %s\n", line.c_str());
}

}  // namespace
}  // namespace tl::test
