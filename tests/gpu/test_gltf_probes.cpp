// The glTF probe scenes of content/ as the G-buffer sees them (every path shades from it):
//   - embedded_textures.glb: both images come out of the .glb, the 16-bit emissive keeps its
//     value on the GPU (1.51, where 8 bits give 0);
//   - normal_probe.gltf: the normal map leans every quad's normal the way the closed form
//     says — towards -dP/dv (the map's green, the image's top) and along dP/du (its red) —
//     whether the tangents were supplied by the file or generated on import.
#include "gpu_fixture.h"

#include "shared/color.h"
#include "shared/packing.h"

#include <map>

namespace tl::test {
namespace {

using GltfProbeTest = GpuTest;

TEST_F(GltfProbeTest, EmbeddedTexturesReachTheGbufferAtTheirPrecision) {
  auto& s = session();
  s.loadScene(contentFile("embedded_textures.glb"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  s.setSize(32, 32);
  s.requestBuffer("gbuffer.baseColor");
  s.requestBuffer("gbuffer.emissive");
  s.renderFrames(1);
  const auto base = s.buffer("gbuffer.baseColor").texels();    // sRGB as stored
  const auto glow = s.buffer("gbuffer.emissive").texels();
  const size_t left = (16 * 32 + 8) * 4, right = (16 * 32 + 24) * 4;
  EXPECT_NEAR(base[left + 0], 188.0f / 255.0f, 1.5f / 255.0f);
  EXPECT_NEAR(base[left + 1], 94.0f / 255.0f, 1.5f / 255.0f);
  EXPECT_NEAR(base[left + 2], 47.0f / 255.0f, 1.5f / 255.0f);
  const float expected = shared::tlSrgbToLinear1(128.0f / 65535.0f) * 1.0e4f;  // 1.5118
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(glow[right + size_t(c)] / expected, 1.0f, 0.01f) << "channel " << c;
  EXPECT_EQ(glow[left], 0.0f) << "the base-colour quad does not glow";
}

TEST_F(GltfProbeTest, NormalMapLeansTheClosedFormWayWithAndWithoutTangents) {
  auto& s = session();
  s.loadScene(contentFile("normal_probe.gltf"));
  EXPECT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
  s.setSize(96, 54);
  s.requestBuffer("gbuffer.normal");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  const auto normals = s.buffer("gbuffer.normal").texels();
  const auto ids = s.buffer("gbuffer.instanceId").texels();
  // The map's texel (8-bit, as stored) in tangent space, and the closed form per quad:
  // n = normalize(T x + B y + N z) with N = +Y, B = -dP/dv = +Z, T = dP/du = +X or -X (mirrored).
  glm::vec3 tn(0.0f);
  const glm::vec3 exact = glm::normalize(glm::vec3(0.3f, 0.5f, 0.81f));
  for (int c = 0; c < 3; ++c) tn[c] = std::round((exact[c] * 0.5f + 0.5f) * 255.0f) / 255.0f * 2.0f - 1.0f;
  const auto& scene = s.scene();
  std::map<std::string, std::pair<glm::dvec3, size_t>> seen;
  for (size_t p = 0; p < ids.size(); ++p) {
    const uint32_t id = uint32_t(ids[p]);
    if (id == 0) continue;
    const std::string& name = scene.instances[id - 1].name;
    const glm::vec3 n = shared::tlOctDecode(glm::vec2(normals[2 * p], normals[2 * p + 1]));
    seen[name].first += glm::dvec3(n);
    ++seen[name].second;
  }
  ASSERT_EQ(seen.size(), 4u) << "all four quads in view";
  for (const auto& [name, sum] : seen) {
    const float t = name.rfind("mirrored", 0) == 0 ? -1.0f : 1.0f;
    const glm::vec3 expected = glm::normalize(glm::vec3(t * tn.x, tn.z, tn.y));
    const glm::vec3 mean = glm::normalize(glm::vec3(sum.first / double(sum.second)));
    EXPECT_GT(sum.second, 20u) << name;
    EXPECT_NEAR(mean.x, expected.x, 0.01f) << name;
    EXPECT_NEAR(mean.y, expected.y, 0.01f) << name;
    EXPECT_NEAR(mean.z, expected.z, 0.01f) << name << ": the bump must lean towards the image's top (+Z)";
  }
}

}  // namespace
}  // namespace tl::test
