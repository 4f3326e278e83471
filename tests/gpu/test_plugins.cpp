// The sample plugins (plugins/) through the Session like any path, on scenes with closed
// forms: `ao` shows the open plane under the sky as white (AO = 1) and `bentsky` gives it the
// irradiance pi L; both are listed after the built-in paths, as plugins.
#include "lighting_checks.h"

#include "shared/packing.h"

#include <algorithm>

namespace tl::test {
namespace {

class PluginTest : public RayTracingTest {};

TEST_F(PluginTest, PluginsAreListedAfterTheBuiltInPaths) {
  std::vector<std::string> plugins, builtIn;
  for (const auto& p : session().paths()) (p.plugin ? plugins : builtIn).push_back(p.name);
  EXPECT_EQ(builtIn, (std::vector<std::string>{"direct", "legacy", "rt", "reference"}));
  EXPECT_EQ(plugins, (std::vector<std::string>{"ao", "bentsky"})) << "plugins, in the order of their names";
}

// The ao plugin on the open plane: every surface pixel white (RTAO with nothing to hit), the
// sky black; in the Cornell box the corners are darker than the open floor.
TEST_F(PluginTest, AoPluginShowsTheOpenPlaneWhiteAndTheBoxCornersDark) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  s.setPath("ao");
  s.setSize(48, 32);
  for (const char* n : {"ao.grey", "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(2);
  auto grey = s.buffer("ao.grey").texels(), depth = s.buffer("gbuffer.depth").texels();
  const uint32_t channels = s.buffer("ao.grey").channels();
  size_t surface = 0;
  double worst = 0.0, sky = 0.0;
  for (size_t i = 0; i < depth.size(); ++i) {
    const float v = grey[channels * i];
    if (depth[i] > 0.0f)
      ++surface, worst = std::max(worst, std::abs(double(v) - 1.0));
    else
      sky = std::max(sky, double(v));
  }
  RecordProperty("worst_ao_error", std::to_string(worst));
  EXPECT_GT(surface, depth.size() / 4);
  EXPECT_LE(worst, 0.005) << "AO of an open plane under the sky is 1";
  EXPECT_EQ(sky, 0.0) << "the sky is black";

  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 32);
  s.requestBuffer("ao.grey");
  s.renderFrames(4);
  grey = s.buffer("ao.grey").texels();
  double darkest = 1.0;
  for (size_t i = 0; i < grey.size(); i += channels) darkest = std::min(darkest, double(grey[i]));
  EXPECT_LT(darkest, 0.7) << "the box's corners are occluded";
}

// The ao plugin traces its own rays by the definition the reference's AO has (cosine rays
// from the primary hit, occluded within rtAoRadius): on the Cornell box, after as many rays
// per pixel as the reference's samples, the two agree per pixel within their noise and in the
// mean within a hundredth; and its frame runs none of the rt path's passes.
TEST_F(PluginTest, AoPluginMatchesTheReferenceAoAndRunsNoRtPass) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  const uint32_t w = 48, h = 48;
  s.settings().referenceSamplesPerFrame = 64;
  renderFresh(s, "reference", w, h, 4, {"reference.ao", "gbuffer.depth"});
  const auto reference = s.buffer("reference.ao").texels(), depth = s.buffer("gbuffer.depth").texels();
  renderFresh(s, "ao", w, h, 128, {"ao.grey"});
  const auto grey = s.buffer("ao.grey").texels();
  const uint32_t channels = s.buffer("ao.grey").channels();
  double meanAbs = 0.0, aoMean = 0.0, referenceMean = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    ++n;
    meanAbs += std::abs(double(grey[channels * i]) - reference[i]);
    aoMean += grey[channels * i], referenceMean += reference[i];
  }
  ASSERT_GT(n, depth.size() / 2);
  meanAbs /= double(n), aoMean /= double(n), referenceMean /= double(n);
  RecordProperty("ao_mean", std::to_string(aoMean));
  RecordProperty("reference_ao_mean", std::to_string(referenceMean));
  RecordProperty("mean_abs_difference", std::to_string(meanAbs));
  EXPECT_LT(referenceMean, 0.97) << "the box has corners: some occlusion";
  EXPECT_NEAR(aoMean, referenceMean, 0.01) << "the same definition, unbiased";
  EXPECT_LT(meanAbs, 0.05) << "per pixel within the two estimates' noise";

  size_t rtPasses = 0, aoPasses = 0;
  for (const auto& [pass, ms] : s.passGpuMs()) {
    rtPasses += pass.rfind("rt.", 0) == 0;
    aoPasses += pass.rfind("ao.", 0) == 0;
  }
  EXPECT_EQ(rtPasses, 0u) << "the plugin borrows the structures, not the rt path";
  EXPECT_EQ(aoPasses, 1u);
}

// bentsky on the open plane: visibility 1 and irradiance pi L at every surface pixel from the
// first frame (every ray escapes; the uniform sky's irradiance does not depend on the bent
// normal); within half-float rounding. In the Cornell box the floor sees less sky than that.
TEST_F(PluginTest, BentSkyPluginGivesTheOpenPlanePiL) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  s.setPath("bentsky");
  s.setSize(48, 32);
  for (const char* n : {"bentsky.ao", "bentsky.shY", "bentsky.coCg", "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(1);
  PlaneErrors e = planeErrors(s, "bentsky.ao", "bentsky.shY", "bentsky.coCg");
  RecordProperty("worst_irradiance_error", std::to_string(e.worstIrradiance));
  EXPECT_GT(e.surface, e.pixels / 4);
  EXPECT_LE(e.worstAo, 1e-3);
  EXPECT_LE(e.worstIrradiance, 2e-3) << "irradiance relative to pi L";

  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 32);
  for (const char* n : {"bentsky.ao", "gbuffer.normal", "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(2);
  auto ao = s.buffer("bentsky.ao").texels(), normal = s.buffer("gbuffer.normal").texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  double floorVisibility = 0.0;
  size_t floorPixels = 0;
  for (size_t i = 0; i < ao.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    if (shared::tlOctDecode(glm::vec2(normal[2 * i], normal[2 * i + 1])).y > 0.95f) floorVisibility += ao[i], ++floorPixels;
  }
  ASSERT_GT(floorPixels, 0u);
  floorVisibility /= double(floorPixels);
  RecordProperty("cornell_floor_visibility", std::to_string(floorVisibility));
  EXPECT_GT(floorVisibility, 0.02) << "the open side lets some sky in";
  EXPECT_LT(floorVisibility, 0.6) << "the walls and the ceiling hide most of it";
}

}  // namespace
}  // namespace tl::test
