// Alpha MASK is the same cut-out in every stage that sees a surface: on content/cutout.gltf a
// quad whose texture's alpha is 0 everywhere hangs 1 m above the floor, under a sun straight
// overhead. Cut out everywhere (G-buffer, shadow map, voxels, the RT path's rays and the
// reference's), the floor under it is as bright as the open floor; a stage that still sees it
// casts a shadow there (the sun is 3/4 of the light) or bleeds its red into it.
//
// Alpha BLEND is stochastic transparency in every stage: content/translucent_pane.gltf's black
// pane of alpha 0.5 lets half the sun through to the floor in every path, and covers half of
// the pixels it spans in the G-buffer.
#include "gpu_fixture.h"

#include "../common/test_scenes.h"

#include <algorithm>
#include <cstdio>

namespace tl::test {
namespace {

using AlphaTest = RayTracingTest;

// Mean RGB of the (2r)^2 pixels around (x, y) of an RGBA image `size` wide.
glm::dvec3 patch(const std::vector<float>& rgba, uint32_t size, uint32_t x, uint32_t y, uint32_t r) {
  glm::dvec3 sum(0.0);
  for (uint32_t j = y - r; j < y + r; ++j)
    for (uint32_t i = x - r; i < x + r; ++i)
      for (int c = 0; c < 3; ++c) sum[c] += rgba[(size_t(j) * size + i) * 4 + size_t(c)];
  return sum / double(4 * r * r);
}

TEST_F(AlphaTest, FloorUnderACutOutQuadIsLitLikeTheOpenFloorInEveryPath) {
  auto& s = session();
  const uint32_t size = 48;
  const double closedForm = 0.8 / glm::pi<double>() * (10.0 + glm::pi<double>());  // rho/pi (E + pi L) = 3.346
  for (const char* path : {"direct", "legacy", "rt", "reference"}) {
    SCOPED_TRACE(path);
    s.loadScene(contentFile("cutout.gltf"));
    ASSERT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
    s.settings().referenceSamplesPerFrame = 4;
    renderFresh(s, path, size, size, std::string(path) == "direct" ? 1 : 8);
    const auto image = s.buffer(finalImageOf(path)).texels();
    // The image centre looks at the floor under the quad's centre; 1/8 of the width in from
    // the left edge sees open floor 2.1 m from it.
    const glm::dvec3 under = patch(image, size, size / 2, size / 2, 2);
    const glm::dvec3 open = patch(image, size, size / 8, size / 2, 2);
    std::printf("[ alpha    ] %-9s under %.4f %.4f %.4f  open %.4f %.4f %.4f  closed form %.4f\n", path, under.r, under.g,
                under.b, open.r, open.g, open.b, closedForm);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(under[c] / open[c], 1.0, 0.02) << "channel " << c << ": under " << under[c] << ", open " << open[c];
      EXPECT_NEAR(open[c] / closedForm, 1.0, 0.02) << "channel " << c;
    }
    EXPECT_NEAR(under.r / under.g, 1.0, 0.01) << "no red from the cut-out quad";
  }
}


// The floor in the pane's shadow against the open floor beside it, on the line x = 1 that
// camera 0's centre row sees: exactly half, and the open floor at its closed form.
TEST_F(AlphaTest, AHalfTranslucentPaneLetsHalfTheSunThroughInEveryPath) {
  auto& s = session();
  const uint32_t size = 64;
  const double open = 0.8 / glm::pi<double>() * 10.0 * std::sqrt(0.5);  // 1.801
  for (const char* path : {"direct", "legacy", "rt", "reference"}) {
    SCOPED_TRACE(path);
    s.loadScene(contentFile("translucent_pane.gltf"));
    ASSERT_TRUE(s.scene().ignored.empty()) << s.scene().ignored.front();
    s.settings().referenceSamplesPerFrame = 16;
    const bool reference = std::string(path) == "reference";
    renderFresh(s, path, size, size, reference ? 16 : std::string(path) == "direct" ? 1 : 8);
    const auto image = s.buffer(finalImageOf(path)).texels();
    // The shadow spans z in [-1, 1] on the centre row, the image's middle third or so; the
    // open floor is beyond it on both sides (1/8 of the width from each edge: z = -/+2.0).
    const glm::dvec3 shadow = patch(image, size, size / 2, size / 2, 6);
    const glm::dvec3 left = patch(image, size, size / 8, size / 2, 2);
    const glm::dvec3 right = patch(image, size, size - size / 8, size / 2, 2);
    std::printf("[ blend    ] %-9s shadow %.4f  open %.4f %.4f  ratio %.4f  closed form %.4f / %.4f\n", path, shadow.g,
                left.g, right.g, shadow.g / (0.5 * (left.g + right.g)), 0.5 * open, open);
    const double tolerance = reference ? 0.02 : 0.05;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(shadow[c] / (0.5 * (left[c] + right[c])), 0.5, 0.5 * tolerance) << "channel " << c;
      EXPECT_NEAR(left[c] / open, 1.0, 0.02) << "channel " << c;
      EXPECT_NEAR(right[c] / open, 1.0, 0.02) << "channel " << c;
    }
  }
}

// Under the sky alone (Lambertian materials: no Fresnel at the grazing view), rays cross the
// pane: an opaque copy hides the share F = 0.5541 of the sky light at the floor under its
// centre (a 2 m square 1 m up: the point-to-parallel-rectangle form factor), the translucent
// pane half of that. The reference is held to both closed forms, 0.8 (1 - F) = 0.3567 and
// 0.8 (1 - F / 2) = 0.5783, rt to them within 8% and 3%; legacy and rt to half their own
// opaque pane's share (each has its own bias under an overhang: rt's screen reuse and what is
// left of its denoiser's, legacy's voxel cones, which see the dithered voxels). The direct path
// has no sky occlusion to test.
TEST_F(AlphaTest, RaysCrossAHalfTranslucentPaneHalfTheTime) {
  auto& s = session();
  const uint32_t size = 64;
  const double formFactor = 4.0 * std::atan(std::sqrt(0.5)) * std::sqrt(0.5) / glm::pi<double>();  // 4 corners, A = B = 1
  const auto skyUnderThePane = [&](const char* path, scene::AlphaMode mode) {
    auto scene = session::Session::parseScene(contentFile("translucent_pane.gltf"));
    for (auto& m : scene->materials)
      if (m.name == "smoked_glass") m.alphaMode = mode;
    s.installScene(std::move(scene));
    session::Lighting skyOnly = s.lighting();
    skyOnly.sunIrradiance = glm::vec3(0.0f);
    skyOnly.skyRadiance = glm::vec3(1.0f);
    s.setLighting(skyOnly);
    s.useSceneCamera(2);
    s.settings().materials = lighting::MaterialMode::Diffuse;
    s.settings().referenceSamplesPerFrame = 16;
    renderFresh(s, path, size, size, std::string(path) == "reference" ? 16 : 32);
    s.settings().materials = lighting::MaterialMode::Authored;
    return patch(s.buffer(finalImageOf(path)).texels(), size, size / 2, size / 2, 2);
  };
  for (const char* path : {"legacy", "rt", "reference"}) {
    SCOPED_TRACE(path);
    const glm::dvec3 opaque = skyUnderThePane(path, scene::AlphaMode::Opaque);
    const glm::dvec3 blend = skyUnderThePane(path, scene::AlphaMode::Blend);
    const glm::dvec3 share = (0.8 - blend) / (0.8 - opaque);
    std::printf("[ blend    ] %-9s sky under the pane: opaque %.4f (closed form %.4f), alpha 0.5 %.4f (%.4f): "
                "hides %.4f of the opaque share\n",
                path, opaque.g, 0.8 * (1.0 - formFactor), blend.g, 0.8 * (1.0 - 0.5 * formFactor), share.g);
    // rt against the closed forms too: its denoiser's radius follows the rays' hit distances,
    // so under the opaque pane it no longer averages in the open floor (measured 6.0% and 0.4%
    // over the closed forms; before, 23% and 6.5%, whose ratio of differences happened to give
    // 0.510). The share, a ratio of differences from 0.8, carries the opaque image's 6% (0.531).
    const std::string name = path;
    const double imageTolerance = name == "reference" ? 0.02 : 0.08, blendTolerance = name == "reference" ? 0.02 : 0.03;
    const double shareTolerance = name == "legacy" ? 0.05 : name == "rt" ? 0.04 : 0.025;
    for (int c = 0; c < 3; ++c) {
      if (name != "legacy") {
        EXPECT_NEAR(opaque[c] / (0.8 * (1.0 - formFactor)), 1.0, imageTolerance) << "channel " << c;
        EXPECT_NEAR(blend[c] / (0.8 * (1.0 - 0.5 * formFactor)), 1.0, blendTolerance) << "channel " << c;
      }
      EXPECT_NEAR(share[c], 0.5, shareTolerance) << "channel " << c;
    }
  }
}

// Camera 1 looks down through the pane: a half-translucent pane covers half the pixels that an
// opaque copy of it covers (the ordered dither keeps every 4x4 block exact), and TAA moves the
// dither each frame so that no pixel keeps the pane.
TEST_F(AlphaTest, AHalfTranslucentPaneCoversHalfItsPixelsInTheGbuffer) {
  auto& s = session();
  const uint32_t size = 96;
  const auto panePixels = [&](scene::AlphaMode mode, uint32_t frameIndex) {
    auto scene = session::Session::parseScene(contentFile("translucent_pane.gltf"));
    for (auto& m : scene->materials)
      if (m.name == "smoked_glass") m.alphaMode = mode;
    const uint32_t pane = instanceIdOf(*scene, "pane");
    s.installScene(std::move(scene));
    s.useSceneCamera(1);
    s.setPath("direct");
    s.setSize(size, size);
    s.setFrameIndex(frameIndex);
    s.requestBuffer("gbuffer.instanceId");
    s.renderFrames(1);  // not renderFresh: the frame index is the test's
    const auto ids = s.buffer("gbuffer.instanceId");
    std::vector<uint8_t> covered(size_t(size) * size);
    const auto* id = reinterpret_cast<const uint32_t*>(ids.bytes.data());
    for (size_t i = 0; i < covered.size(); ++i) covered[i] = id[i] == pane;
    return covered;
  };
  const auto count = [](const std::vector<uint8_t>& v) { return std::count(v.begin(), v.end(), uint8_t(1)); };
  const auto opaque = panePixels(scene::AlphaMode::Opaque, 0);
  const auto still = panePixels(scene::AlphaMode::Blend, 0);
  ASSERT_GT(count(opaque), 1000) << "camera 1 sees the pane";
  const double fraction = double(count(still)) / double(count(opaque));
  std::printf("[ blend    ] pane pixels: opaque %td, alpha 0.5 %td (%.4f)\n", count(opaque), count(still), fraction);
  EXPECT_NEAR(fraction, 0.5, 0.02);
  for (size_t i = 0; i < still.size(); ++i) ASSERT_LE(still[i], opaque[i]) << "pixel " << i << " outside the pane";

  // With TAA the dither moves: over 8 frames every pane pixel shows the pane on some frames
  // and the floor on others; without it the same pixels keep it (no flicker).
  s.settings().taa = true;
  std::vector<int> seen(opaque.size(), 0);
  for (uint32_t f = 0; f < 8; ++f) {
    const auto frame = panePixels(scene::AlphaMode::Blend, f);
    for (size_t i = 0; i < frame.size(); ++i) seen[i] += frame[i];
  }
  s.settings().taa = false;
  size_t always = 0, never = 0, inside = 0;
  for (size_t i = 0; i < opaque.size(); ++i) {
    if (!opaque[i]) continue;
    ++inside;
    always += seen[i] == 8;
    never += seen[i] == 0;
  }
  std::printf("[ blend    ] with TAA over 8 frames: %zu of %zu pane pixels always the pane, %zu never\n", always, inside,
              never);
  EXPECT_LT(double(always + never), 0.05 * double(inside));
  EXPECT_EQ(panePixels(scene::AlphaMode::Blend, 5), still) << "without TAA the dither stands still";
}

}  // namespace
}  // namespace tl::test
