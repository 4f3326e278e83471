// The Compare panel's engine side: sides and the reference render in turn, the wipe shows
// each side's own image on its side of the line, the difference of a path with itself is
// zero, and the live error is measured only against a reference of the same view.
#include "gpu_fixture.h"

#include "lighting/common/compare_view_pass.h"
#include "lighting/common/display_pass.h"
#include "session/compare.h"
#include "shared/display.h"

namespace tl::test {
namespace {

class CompareViewTest : public RayTracingTest {
 protected:
  // Renders n frames reading back the compare view and both sides' images.
  void render(uint32_t n, const session::CompareView& v) {
    auto& s = session();
    for (uint32_t i = 0; i < n; ++i) {
      s.requestBuffer(lighting::kDisplayLdr);
      for (const std::string& p : {v.left, v.right}) s.requestBuffer(lighting::compareImageName(p));
      s.renderFrames(1);
    }
  }
};

TEST_F(CompareViewTest, WipeShowsEachSidesOwnImageAndErrorsAreMeasured) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 24);
  s.settings().referenceSamplesPerFrame = 4;
  session::CompareView v;
  v.left = "direct";
  v.right = "legacy";
  v.wipe = 0.5f;
  s.setCompareView(v);
  render(6, v);  // direct, legacy, reference, twice
  auto* live = s.liveCompare();
  ASSERT_NE(live, nullptr);
  live->finishFlip();  // FLIP runs on a worker thread, beside the frames
  EXPECT_EQ(live->referenceSamples(), 8u);
  auto errors = live->errors();
  ASSERT_EQ(errors.size(), 2u);
  for (const auto& e : errors) {
    ASSERT_TRUE(e.relMse.has_value()) << e.path;
    EXPECT_TRUE(std::isfinite(*e.relMse)) << e.path;
    EXPECT_GT(*e.relMse, 0.0) << e.path;
    ASSERT_TRUE(e.flip.has_value()) << e.path;
    EXPECT_GT(e.gpuMs, 0.0) << e.path;
  }

  // The displayed pixels are each side's image, tonemapped like the final image.
  const float exposure = std::exp2(-s.exposureEv());
  auto sideDisplay = [&](const std::string& path) {
    return session::displayEncode(session::rgbImage(s.buffer(lighting::compareImageName(path))), exposure);
  };
  metrics::Image left = sideDisplay("direct"), right = sideDisplay("legacy");
  auto shown = s.buffer(lighting::kDisplayLdr).texels();
  const uint32_t w = 32, split = 16;
  double worstLeft = 0.0, worstRight = 0.0, sidesDiffer = 0.0;
  for (uint32_t y = 0; y < 24; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      if (x == split || x + 1 == split) continue;  // the wipe line
      for (uint32_t k = 0; k < 3; ++k) {
        const float d = shown[(size_t(y) * w + x) * 4 + k];
        const float expected = x < split ? left.at(x, y, k) : right.at(x, y, k);
        (x < split ? worstLeft : worstRight) = std::max(x < split ? worstLeft : worstRight, double(std::abs(d - expected)));
        sidesDiffer = std::max(sidesDiffer, double(std::abs(left.at(x, y, k) - right.at(x, y, k))));
      }
    }
  EXPECT_LT(worstLeft, 1.5 / 255.0);
  EXPECT_LT(worstRight, 1.5 / 255.0);
  EXPECT_GT(sidesDiffer, 0.05) << "legacy adds bounce light the direct path lacks";
  EXPECT_FLOAT_EQ(shown[(size_t(5) * w + split) * 4], 1.0f) << "the wipe line";
}

TEST_F(CompareViewTest, DifferenceOfAPathWithItselfIsZeroAndAMovedCameraWaitsForItsReference) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(24, 24);
  session::CompareView v;
  v.left = v.right = "direct";
  v.difference = true;
  s.setCompareView(v);
  render(2, v);  // direct, reference
  auto shown = s.buffer(lighting::kDisplayLdr).texels();
  const glm::vec3 zero = shared::tlDisplayFalseColour(0.0f);
  double worst = 0.0;
  for (size_t i = 0; i < shown.size(); i += 4)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(shown[i + k] - zero[k])));
  EXPECT_LT(worst, 1.5 / 255.0);
  ASSERT_EQ(s.liveCompare()->errors().size(), 1u);
  EXPECT_TRUE(s.liveCompare()->errors()[0].relMse.has_value());

  // A new view: the side renders first, and its old reference no longer matches it.
  session::View view = s.view();
  view.position.x += 0.2;
  s.setView(view);
  render(1, v);
  EXPECT_FALSE(s.liveCompare()->errors()[0].relMse.has_value()) << "measured against the reference of another view";
  render(1, v);
  EXPECT_TRUE(s.liveCompare()->errors()[0].relMse.has_value());
}

// The live reference follows the camera: a 0.2 m sideways step (no cut, no turn) restarts its
// sum, and the panel's figures say so and why.
TEST_F(CompareViewTest, ASidewaysStepRestartsTheLiveReference) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(24, 24);
  s.settings().referenceSamplesPerFrame = 4;
  session::CompareView v;
  v.left = "direct";
  v.right = "legacy";
  s.setCompareView(v);
  render(6, v);  // direct, legacy, reference, twice
  const auto* live = s.liveCompare();
  ASSERT_NE(live, nullptr);
  EXPECT_EQ(live->referenceSamples(), 8u);
  EXPECT_EQ(live->referenceRestarts(), 0u) << "the first sum is a start, not a restart";
  session::View view = s.view();
  view.position += 0.2 * glm::normalize(glm::cross(view.forward, view.up));
  s.setView(view);
  render(3, v);
  std::printf("live reference: 8 samples per pixel before the step, %u after one reference frame past it\n",
              live->referenceSamples());
  EXPECT_EQ(live->referenceSamples(), 4u) << "the sum restarted at the new position";
  EXPECT_EQ(live->referenceRestarts(), 1u);
  EXPECT_EQ(live->lastReferenceRestart(), lighting::partBit(lighting::FramePart::CameraPosition))
      << lighting::describeParts(live->lastReferenceRestart());
  for (const auto& e : live->errors()) EXPECT_TRUE(e.relMse.has_value()) << e.path << " measured against the new view";
  render(3, v);
  EXPECT_EQ(live->referenceSamples(), 8u);
  EXPECT_EQ(live->referenceRestarts(), 1u) << "a still camera accumulates";
}

TEST_F(CompareViewTest, AnUnavailableSideIsRefusedAndNothingChanges) {
  auto& s = session();
  session::CompareView v;
  v.left = "direct";
  v.right = "no-such-path";
  EXPECT_THROW(s.setCompareView(v), session::SessionError);
  EXPECT_EQ(s.liveCompare(), nullptr) << "no compare view was open: none is";
  // With one open, a refused change keeps it as it was.
  session::CompareView open;
  open.left = "direct";
  open.right = "legacy";
  open.wipe = 0.3f;
  s.setCompareView(open);
  EXPECT_THROW(s.setCompareView(v), session::SessionError);
  ASSERT_NE(s.liveCompare(), nullptr);
  EXPECT_EQ(s.liveCompare()->view().left, "direct");
  EXPECT_EQ(s.liveCompare()->view().right, "legacy");
  EXPECT_EQ(s.liveCompare()->view().wipe, 0.3f);
}

}  // namespace
}  // namespace tl::test
