// The RT path's traced reflections (shared/rt_specular.h): energy against a closed form, the
// mirror path against the reference, and what the reflections change against the reference
// on the polished-metal Cornell box.
#include "furnace_checks.h"

#include "lighting/common/composite_pass.h"
#include "lighting/rt/rt_path.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace tl::test {
namespace {

// The traced roughness the tests use (RE ENGINE-like; the setting is off by default).
constexpr float kTraced = 0.5f;

class ReflectionsTest : public RayTracingTest {};

// White metal spheres (mirror, 0.15, 0.35) under a uniform sky of 1: every pixel is exactly 1,
// spheres seen in spheres included. direct (no inter-reflection) must be exact per pixel. rt's
// mean must be 1 within 0.5%; its worst pixel (measured 0.062 after 16 + 16 frames) is the
// mirror's unfiltered noise where it shows another sphere, whose hit is lit through one sky ray
// a frame, so it is held to 0.1. legacy's mean holds (0.992) but its cones see the
// neighbouring spheres dark (worst pixel 0.71, measured): recorded, not asserted, a known limit.
TEST_F(ReflectionsTest, PolishedMetalFurnaceShowsOneEverywhere) {
  auto& s = session();
  s.loadScene(contentFile("metal_furnace.gltf"));
  s.setSize(48, 32);
  s.settings().rtReflectionRoughness = kTraced;
  struct Bound {
    const char* path;
    double mean, worst;  // |mean - 1| and the worst |pixel - 1| allowed (0: not asserted)
  };
  for (const Bound& b : {Bound{"rt", 0.005, 0.1}, Bound{"legacy", 0.01, 0.0}, Bound{"direct", 0.001, 0.01}}) {
    s.setPath(b.path);
    s.resetHistory();
    uint32_t channels = 0;
    s.renderFrames(16);
    const std::vector<float> image = averagedFrames(s, lighting::kCompositeHdr, 16, channels);  // sets channels
    const FurnaceStats st = furnaceStats(image, channels);
    std::printf("metal furnace, %-6s mean %.4f, max |v-1| %.4f\n", b.path, st.mean, st.worst);
    RecordProperty(std::string(b.path) + "_mean", std::to_string(st.mean));
    RecordProperty(std::string(b.path) + "_max", std::to_string(st.worst));
    EXPECT_EQ(st.nonFinite, 0u) << b.path;
    EXPECT_LT(std::abs(st.mean - 1.0), b.mean) << b.path << ": a white metal under a sky of 1 shows 1";
    if (b.worst > 0.0) {
      EXPECT_LT(st.worst, b.worst) << b.path;
    }
  }
  s.settings() = lighting::RenderSettings{};
}

// The traced estimate is what the composite shows below the threshold: with the threshold at 0
// nothing is traced and rt.specular is not in the frame.
TEST_F(ReflectionsTest, ReflectionsAreTracedOnlyBelowTheirRoughness) {
  auto& s = session();
  s.loadScene(contentFile("polished_metals.gltf"));
  s.setSize(64, 36);
  s.setPath("rt");
  s.settings().rtReflectionRoughness = kTraced;
  s.resetHistory();
  s.requestBuffer(lighting::kSpecularRaw);
  s.requestBuffer("gbuffer.material");
  s.requestBuffer("gbuffer.depth");
  s.renderFrames(2);
  auto raw = s.buffer(lighting::kSpecularRaw).texels();
  auto material = s.buffer("gbuffer.material").texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  const uint32_t mc = s.buffer("gbuffer.material").channels();
  const float threshold = s.settings().rtReflectionRoughness;
  size_t traced = 0, wrong = 0, smooth = 0;
  for (size_t i = 0; i < depth.size(); ++i) {
    const bool isTraced = raw[4 * i + 3] > 0.0f;
    const bool shouldTrace = depth[i] > 0.0f && material[mc * i] < threshold;
    traced += isTraced;
    smooth += shouldTrace;
    wrong += isTraced != shouldTrace;
  }
  std::printf("pixels traced %zu of %zu below roughness %.2f (%zu wrong)\n", traced, smooth, threshold, wrong);
  EXPECT_GT(smooth, depth.size() / 10) << "the scene shows smooth surfaces";
  EXPECT_EQ(wrong, 0u);

  s.settings().rtReflectionRoughness = 0.0f;
  s.requestBuffer(lighting::kSpecular);
  s.renderFrames(1);
  EXPECT_FALSE(s.hasBuffer(lighting::kSpecular)) << "no reflection passes with the threshold at 0";
  s.settings() = lighting::RenderSettings{};
  s.setSize(64, 36);
}

}  // namespace
}  // namespace tl::test
