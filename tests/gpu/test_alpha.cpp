// Alpha MASK is the same cut-out in every stage that sees a surface: on content/cutout.gltf a
// quad whose texture's alpha is 0 everywhere hangs 1 m above the floor, under a sun straight
// overhead. Cut out everywhere (G-buffer, shadow map, voxels, the RT path's rays and the
// reference's), the floor under it is as bright as the open floor; a stage that still sees it
// casts a shadow there (the sun is 3/4 of the light) or bleeds its red into it.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"

#include <cstdio>

namespace tl::test {
namespace {

using AlphaTest = RayTracingTest;

const char* finalImage(const std::string& path) { return path == "reference" ? "reference.radiance" : lighting::kCompositeHdr; }

// Mean RGB of the 4x4 pixels around (x, y) of an RGBA image `size` wide.
glm::dvec3 patch(const std::vector<float>& rgba, uint32_t size, uint32_t x, uint32_t y) {
  glm::dvec3 sum(0.0);
  for (uint32_t j = y - 2; j < y + 2; ++j)
    for (uint32_t i = x - 2; i < x + 2; ++i)
      for (int c = 0; c < 3; ++c) sum[c] += rgba[(size_t(j) * size + i) * 4 + size_t(c)];
  return sum / 16.0;
}

TEST_F(AlphaTest, FloorUnderACutOutQuadIsLitLikeTheOpenFloorInEveryPath) {
  auto& s = session();
  const uint32_t size = 48;
  const double closedForm = 0.8 / glm::pi<double>() * (10.0 + glm::pi<double>());  // rho/pi (E + pi L) = 3.346
  for (const char* path : {"direct", "legacy", "rt", "reference"}) {
    SCOPED_TRACE(path);
    s.loadScene(contentFile("cutout.gltf"));
    ASSERT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
    s.setPath(path);
    s.setSize(size, size);
    s.settings().referenceSamplesPerFrame = 4;
    s.setFrameIndex(0);
    s.resetHistory();
    const uint32_t frames = std::string(path) == "direct" ? 1 : 8;
    s.renderFrames(frames - 1);
    s.requestBuffer(finalImage(path));
    s.renderFrames(1);
    const auto image = s.buffer(finalImage(path)).texels();
    // The image centre looks at the floor under the quad's centre; 1/8 of the width in from
    // the left edge sees open floor 2.1 m from it.
    const glm::dvec3 under = patch(image, size, size / 2, size / 2);
    const glm::dvec3 open = patch(image, size, size / 8, size / 2);
    std::printf("[ alpha    ] %-9s under %.4f %.4f %.4f  open %.4f %.4f %.4f  closed form %.4f\n", path, under.r, under.g,
                under.b, open.r, open.g, open.b, closedForm);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(under[c] / open[c], 1.0, 0.02) << "channel " << c << ": under " << under[c] << ", open " << open[c];
      EXPECT_NEAR(open[c] / closedForm, 1.0, 0.02) << "channel " << c;
    }
    EXPECT_NEAR(under.r / under.g, 1.0, 0.01) << "no red from the cut-out quad";
  }
}

}  // namespace
}  // namespace tl::test
