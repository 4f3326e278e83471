// Temporal anti-aliasing (lighting/common/taa_pass.h, shared/taa.h) on lavapipe: a still
// camera's motion vectors stay zero under the jitter; the resolved image of the direct path
// on cornell approaches the same path supersampled 4x4, closer than the aliased frame; and
// the neighbourhood clip follows a light switched off within one frame.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/taa_pass.h"
#include "shared/color.h"
#include "shared/taa.h"

namespace tl::test {
namespace {

using lighting::RenderSettings;

// Mean luminance of a read-back RGBA image.
double meanLuminance(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) sum += shared::tlLuminance(glm::vec3(rgba[i], rgba[i + 1], rgba[i + 2]));
  return sum / double(std::max<size_t>(rgba.size() / 4, 1));
}

TEST(TaaJitter, HaltonOffsetsCoverThePixelEvenly) {
  glm::vec2 sum(0.0f);
  for (uint32_t i = 0; i < shared::kTaaJitterLength; ++i) {
    glm::vec2 o = shared::tlTaaJitterPixels(i);
    EXPECT_GT(o.x, -0.5f);
    EXPECT_LT(o.x, 0.5f);
    EXPECT_GT(o.y, -0.5f);
    EXPECT_LT(o.y, 0.5f);
    sum += o;
  }
  EXPECT_NEAR(shared::tlHalton(1, 2), 0.5f, 1e-6f);
  EXPECT_NEAR(shared::tlHalton(2, 3), 2.0f / 3.0f, 1e-6f);
  // Eight Halton points average near the pixel centre.
  EXPECT_LT(std::abs(sum.x / 8.0f), 0.07f);
  EXPECT_LT(std::abs(sum.y / 8.0f), 0.07f);
  // Clipping towards the box centre: inside stays, outside lands on the box.
  glm::vec3 inside(0.5f), outside(3.0f, 0.5f, 0.5f);
  EXPECT_EQ(shared::tlTaaClipToBox(inside, glm::vec3(0.0f), glm::vec3(1.0f)), inside);
  glm::vec3 c = shared::tlTaaClipToBox(outside, glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_NEAR(c.x, 1.0f, 1e-6f);
  EXPECT_NEAR(c.y, 0.5f, 1e-6f);
}

TEST_F(GpuTest, StillCameraHasZeroMotionUnderTheJitter) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.settings().taa = true;
  s.setPath("direct");
  s.setSize(48, 48);
  s.requestBuffer("gbuffer.motion");
  s.renderFrames(3);
  auto m = s.buffer("gbuffer.motion").texels();
  float worst = 0.0f;
  for (float v : m) worst = std::max(worst, std::abs(v));
  EXPECT_LT(worst, 1e-5f) << "the jitter leaked into the motion vectors";
  EXPECT_NE(s.graphDump().find("taa"), std::string::npos);
}

// The direct path on cornell (sharp box edges, no noise): its image at 64x64 with TAA after
// 32 frames against the same path rendered at 256x256 and box-filtered to 64x64.
TEST_F(GpuTest, TaaApproachesTheSupersampledImage) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setPath("direct");
  const uint32_t n = 64, k = 4;
  s.setSize(n * k, n * k);
  s.renderFrames(1);
  auto big = s.buffer(lighting::kCompositeHdr).texels();
  std::vector<double> supersampled(n * n * 3, 0.0);
  for (uint32_t y = 0; y < n * k; ++y)
    for (uint32_t x = 0; x < n * k; ++x)
      for (int c = 0; c < 3; ++c) supersampled[3 * ((y / k) * n + x / k) + c] += big[4 * (y * n * k + x) + c] / double(k * k);
  auto errorOf = [&](bool taa) {
    s.settings().taa = taa;
    s.setSize(n, n);
    s.resetHistory();
    s.renderFrames(32);
    auto img = s.buffer(lighting::kCompositeHdr).texels();
    EXPECT_EQ(countNonFinite(img), 0u);
    double sum = 0.0;
    for (uint32_t i = 0; i < n * n; ++i)
      for (int c = 0; c < 3; ++c) {
        double d = img[4 * i + c] - supersampled[3 * i + c];
        sum += d * d;
      }
    return std::sqrt(sum / double(n * n * 3));
  };
  const double aliased = errorOf(false), resolved = errorOf(true);
  std::printf("RMSE against 4x4 supersampling: aliased %.4f, TAA %.4f\n", aliased, resolved);
  RecordProperty("rmse_aliased", std::to_string(aliased));
  RecordProperty("rmse_taa", std::to_string(resolved));
  EXPECT_LT(resolved, 0.75 * aliased);
}

// The history is clipped to the current neighbourhood: when the light goes off, the resolved
// image follows within a frame instead of fading over ten.
TEST_F(GpuTest, TaaHistoryFollowsALightSwitchedOff) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  s.settings().taa = true;
  s.setPath("direct");
  s.setSize(48, 32);
  const session::Lighting day = s.lighting();
  s.resetHistory();
  s.renderFrames(16);
  const double lit = meanLuminance(s.buffer(lighting::kCompositeHdr).texels());
  session::Lighting dusk = day;
  dusk.skyRadiance *= 0.1f;
  dusk.sunIrradiance *= 0.1f;
  s.setLighting(dusk);
  s.renderFrames(1);
  const double after = meanLuminance(s.buffer(lighting::kCompositeHdr).texels());
  s.setLighting(day);
  std::printf("mean luminance lit %.4f, one frame after dimming to 10%%: %.4f\n", lit, after);
  EXPECT_LT(after, 0.12 * lit) << "an unclipped 0.1 blend would leave about 0.91 of the old light";
}

}  // namespace
}  // namespace tl::test
