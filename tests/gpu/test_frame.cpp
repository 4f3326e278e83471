// The whole frame on lavapipe with validation on: every graph resource is finite, the
// image is lit, the graph names every resource with its writer.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"

#include <set>

namespace tl::test {

TEST_F(GpuTest, AtriumRendersFiniteLitFrameWithEveryResourceNamed) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  s.setPath("direct");
  s.setSize(160, 90);
  s.requestAllBuffers();
  s.renderFrames(2);

  ASSERT_FALSE(s.resources().empty());
  size_t checked = 0;
  for (const auto& r : s.resources()) {
    if (r.imported) continue;
    const graph::Readback& rb = s.buffer(r.name);
    auto texels = rb.texels();
    ASSERT_FALSE(texels.empty()) << r.name;
    EXPECT_EQ(countNonFinite(texels), 0u) << "non-finite values in " << r.name;
    ++checked;
  }
  EXPECT_GE(checked, 9u);  // 6 G-buffer channels + depth + shadow + composite + tonemap

  // Lit and not flat: mean display luminance well above black, and contrast exists.
  auto ldr = s.buffer(lighting::kTonemapLdr).texels();
  double sum = 0, sumSq = 0;
  size_t n = ldr.size() / 4;
  for (size_t i = 0; i < n; ++i) {
    double y = 0.2126 * ldr[4 * i] + 0.7152 * ldr[4 * i + 1] + 0.0722 * ldr[4 * i + 2];
    sum += y;
    sumSq += y * y;
  }
  double mean = sum / n, var = sumSq / n - mean * mean;
  EXPECT_GT(mean, 0.1);
  EXPECT_GT(std::sqrt(var), 0.05);

  // The dump names every resource of the frame and its writer.
  std::string dump = s.graphDump();
  for (const auto& r : s.resources()) {
    EXPECT_NE(dump.find(r.name), std::string::npos) << r.name;
    if (!r.imported) {
      EXPECT_NE(dump.find("written by " + r.writer), std::string::npos) << r.writer;
    }
  }
}

TEST_F(GpuTest, GbufferInstanceIdsMatchSceneInstances) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(96, 96);
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  auto ids = s.buffer("gbuffer.instanceId").texels();
  size_t maxId = s.scene().instances.size();
  size_t covered = 0;
  for (float id : ids) {
    EXPECT_LE(id, float(maxId));
    covered += id > 0.0f;
  }
  EXPECT_GT(covered, ids.size() / 2);  // the box fills most of the view
  // No sun in cornell: nothing reads the shadow map, so the graph culls its pass.
  EXPECT_NE(s.graphDump().find("shadow.sun (nobody reads shadow.sunDepth)"), std::string::npos) << s.graphDump();
  for (const auto& t : s.timings()) EXPECT_NE(t.pass, "shadow.sun");
}

// The grove's ten thousand instances (trees of three meshes over a ground) are drawn by one
// multi-draw call per raster pass, each draw with its own instance: the G-buffer shows
// thousands of distinct instance ids, and the shadow map and G-buffer together record a few
// calls for all their draws. (One call per instance cost the validation layers half a minute
// per test on this scene.)
TEST_F(GpuTest, TenThousandInstancesDrawInOneCallPerPassEachAsItself) {
  auto& s = session();
  s.loadScene(contentFile("grove.gltf"));
  ASSERT_GT(s.scene().instances.size(), 10000u);
  s.useSceneCamera(1);  // from above the trees (the first camera stands on the ground)
  s.setSize(160, 90);
  s.requestBuffer("gbuffer.instanceId");
  const uint64_t callsBefore = s.gpuScene().drawCalls(), drawsBefore = s.gpuScene().instanceDraws();
  s.renderFrames(1);
  const uint64_t calls = s.gpuScene().drawCalls() - callsBefore, draws = s.gpuScene().instanceDraws() - drawsBefore;
  std::set<float> ids;
  for (float id : s.buffer("gbuffer.instanceId").texels())
    if (id > 0.0f) ids.insert(id);
  RecordProperty("draw_calls", std::to_string(calls));
  RecordProperty("instance_draws", std::to_string(draws));
  RecordProperty("distinct_instances_seen", std::to_string(ids.size()));
  EXPECT_GE(draws, 2 * s.scene().instances.size()) << "the G-buffer and the sun's shadow map draw every instance";
  if (s.device().multiDrawIndirect()) {
    EXPECT_LE(calls, 4u) << "one multi-draw call per raster pass";
  }
  EXPECT_GT(ids.size(), 500u) << "each draw is its own instance (its transform, its id)";
}

}  // namespace tl::test
