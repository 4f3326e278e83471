// glTF doubleSided on content/one_sided_probe.gltf: five quads against the sky,
// single-sided and double-sided, facing the camera or away from it, two of them through a
// mirroring transform (glTF then reads their winding clockwise). What each must show:
//   - the G-buffer (the view of every real-time path) holds the three drawn quads and not the
//     two single-sided ones seen from behind; the kept back of the double-sided quad and the
//     mirrored front face the camera;
//   - in every path and the reference, the sky shows where the culled quads stand (the camera
//     rays pass them as the raster does), and every quad, culled or not, still shadows the
//     ground behind it: culling is for the camera only (shared/scene.h states the choice).
#include "gpu_fixture.h"

#include "session/view_math.h"
#include "shared/packing.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace tl::test {
namespace {

constexpr uint32_t kWidth = 192, kHeight = 108;

struct Quad {
  const char* name;
  float x;     // its centre is at (x, 1.2, 0)
  bool drawn;  // what the camera must see of it
};
constexpr Quad kQuads[] = {{"front_drawn", -2.0f, true},
                           {"back_culled", -1.0f, false},
                           {"double_back_drawn", 0.0f, true},
                           {"mirrored_front_drawn", 1.0f, true},
                           {"mirrored_back_culled", 2.0f, false}};

// The pixel a world point projects to through the session's view.
size_t pixelOf(const session::Session& s, glm::dvec3 world) {
  const auto m = session::cameraMatrices(s.view(), double(kWidth) / double(kHeight));
  const glm::dvec4 clip = m.viewProj * glm::dvec4(world - s.view().position, 1.0);
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const auto x = uint32_t(std::floor((ndc.x * 0.5 + 0.5) * kWidth));
  const auto y = uint32_t(std::floor((ndc.y * 0.5 + 0.5) * kHeight));
  EXPECT_LT(x, kWidth);
  EXPECT_LT(y, kHeight);
  return size_t(std::min(y, kHeight - 1)) * kWidth + std::min(x, kWidth - 1);
}

// The mean RGB of the 3x3 pixels around p in an image of `channels` channels.
glm::dvec3 meanAround(const std::vector<float>& image, uint32_t channels, size_t p) {
  glm::dvec3 sum(0.0);
  const int px = int(p % kWidth), py = int(p / kWidth);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const size_t q = size_t(py + dy) * kWidth + size_t(px + dx);
      for (int c = 0; c < 3; ++c) sum[c] += image[q * channels + size_t(c)];
    }
  return sum / 9.0;
}

using DoubleSidedTest = GpuTest;

TEST_F(DoubleSidedTest, GbufferDrawsSingleSidedSurfacesFromTheFrontOnly) {
  auto& s = session();
  s.loadScene(contentFile("one_sided_probe.gltf"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  renderFresh(s, "direct", kWidth, kHeight, 1, {"gbuffer.instanceId", "gbuffer.normal"});
  const auto ids = s.buffer("gbuffer.instanceId").texels();
  const auto normals = s.buffer("gbuffer.normal").texels();
  std::map<std::string, std::pair<size_t, glm::dvec3>> seen;  // pixels, sum of normals
  for (size_t p = 0; p < ids.size(); ++p) {
    const auto id = uint32_t(ids[p]);
    if (id == 0) continue;
    auto& e = seen[s.scene().instances[id - 1].name];
    ++e.first;
    e.second += glm::dvec3(shared::tlOctDecode(glm::vec2(normals[2 * p], normals[2 * p + 1])));
  }
  for (const Quad& q : kQuads) {
    const size_t centre = pixelOf(s, {q.x, 1.2, 0.0});
    const std::string shown = ids[centre] == 0.0f ? "sky" : s.scene().instances[size_t(ids[centre]) - 1].name;
    const size_t pixels = seen.count(q.name) ? seen[q.name].first : 0;
    std::printf("[ one-sided ] %-21s %4zu pixels, its centre shows %s\n", q.name, pixels, shown.c_str());
    if (q.drawn) {
      EXPECT_GT(pixels, 60u) << q.name;
      EXPECT_EQ(shown, q.name);
      // The normal faces the camera: the back's turned over, the mirrored front's as authored.
      const glm::dvec3 n = glm::normalize(seen[q.name].second);
      EXPECT_GT(n.z, 0.99) << q.name << ": normal " << n.x << " " << n.y << " " << n.z;
    } else {
      EXPECT_EQ(pixels, 0u) << q.name << " is seen from behind and single-sided";
      EXPECT_EQ(shown, "sky") << q.name;
    }
  }
}

class DoubleSidedPathTest : public RayTracingTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(DoubleSidedPathTest, CulledQuadsShowTheSkyAndEveryQuadStillCastsItsShadow) {
  const std::string path = GetParam();
  auto& s = session();
  s.loadScene(contentFile("one_sided_probe.gltf"));
  s.settings().referenceSamplesPerFrame = 16;
  const bool reference = path == "reference";
  renderFresh(s, path, kWidth, kHeight, reference ? 4 : 16);
  const auto image = s.buffer(finalImageOf(path)).texels();
  const uint32_t channels = s.buffer(finalImageOf(path)).channels();
  // The sky straight above the quads' row: what the culled quads must let through.
  const glm::dvec3 sky = meanAround(image, channels, pixelOf(s, {0.0, 2.2, 0.0}));
  for (const Quad& q : kQuads) {
    const glm::dvec3 centre = meanAround(image, channels, pixelOf(s, {q.x, 1.2, 0.0}));
    // The sun travels along (0, -1, -1.5): the quad's centre shadows the ground at z = -1.8.
    const glm::dvec3 shadowed = meanAround(image, channels, pixelOf(s, {q.x, 0.0, -1.8}));
    const glm::dvec3 open = meanAround(image, channels, pixelOf(s, {q.x, 0.0, 1.0}));
    const double skyDifference = glm::length(centre - sky) / glm::length(sky);
    const double shadowRatio = shared::tlLuminance(glm::vec3(shadowed)) / shared::tlLuminance(glm::vec3(open));
    std::printf("[ one-sided ] %-9s %-21s centre vs sky %.4f, shadowed / open ground %.3f\n", path.c_str(), q.name,
                skyDifference, shadowRatio);
    if (q.drawn)
      EXPECT_GT(skyDifference, 0.2) << path << " " << q.name << " must be drawn";
    else
      EXPECT_LT(skyDifference, 0.01) << path << " " << q.name << " must show the sky behind it";
    EXPECT_LT(shadowRatio, 0.6) << path << " " << q.name << " must shadow the ground behind it";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPath, DoubleSidedPathTest, ::testing::Values("legacy", "rt", "reference"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace tl::test
