// Camera-relative rendering: the same scene 10^6 m from the world origin renders like the
// original, and motion vectors match the CPU projection of a known camera move.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "session/view_math.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

// Writes a copy of `scene` with every root node moved by `offset`.
fs::path movedCopy(const char* scene, const glm::dvec3& offset, const fs::path& dir) {
  fs::create_directories(dir);
  auto json = nlohmann::json::parse(std::ifstream(contentFile(scene)));
  for (auto& node : json["nodes"]) {
    std::vector<double> t = node.contains("translation") ? node["translation"].get<std::vector<double>>()
                                                         : std::vector<double>{0, 0, 0};
    node["translation"] = {t[0] + offset.x, t[1] + offset.y, t[2] + offset.z};
  }
  std::string stem = fs::path(scene).stem().string();
  fs::copy_file(contentFile((stem + ".bin").c_str()), dir / (stem + ".bin"), fs::copy_options::overwrite_existing);
  fs::path out = dir / scene;
  std::ofstream(out) << json.dump();
  return out;
}

std::vector<float> renderHdr(session::Session& s, const fs::path& scene) {
  s.loadScene(scene);
  s.setSize(64, 64);
  s.renderFrames(1);
  return s.buffer(lighting::kCompositeHdr).texels();
}

}  // namespace

TEST_F(GpuTest, SceneFarFromTheOriginRendersLikeTheOriginal) {
  auto& s = session();
  fs::path dir = fs::temp_directory_path() / "twinlight-far";
  auto near = renderHdr(s, contentFile("cornell.gltf"));
  auto far = renderHdr(s, movedCopy("cornell.gltf", {1.0e6, 0.0, -1.0e6}, dir));
  ASSERT_EQ(near.size(), far.size());
  double maxDiff = 0.0, sum = 0.0;
  for (size_t i = 0; i < near.size(); ++i) {
    maxDiff = std::max(maxDiff, double(std::abs(near[i] - far[i])));
    sum += near[i];
  }
  ASSERT_GT(sum, 0.0);
  // World positions 10^6 m out have a float spacing of 6 cm; camera-relative ones do not.
  EXPECT_LT(maxDiff, 0.02) << "the image changed when the scene moved away from the origin";
  fs::remove_all(dir);
}

TEST_F(GpuTest, MotionVectorsMatchTheCameraMove) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(64, 64);
  session::View v0 = s.view();
  s.renderFrames(1);
  session::View v1 = v0;
  v1.position += glm::dvec3(0.05, 0.02, 0.0);
  s.setView(v1);
  s.requestBuffer("gbuffer.motion");
  s.requestBuffer("gbuffer.depth");
  s.renderFrames(1);
  auto motion = s.buffer("gbuffer.motion").texels();
  auto depth = s.buffer("gbuffer.depth").texels();

  // Reconstruct the centre pixel's point from depth, project it with both cameras.
  const uint32_t x = 32, y = 32;
  float d = depth[y * 64 + x];
  ASSERT_GT(d, 0.0f);
  auto cur = session::cameraMatrices(v1, 1.0).viewProj;
  glm::dvec2 ndc((x + 0.5) / 64.0 * 2.0 - 1.0, (y + 0.5) / 64.0 * 2.0 - 1.0);
  glm::dvec4 rel = glm::inverse(cur) * glm::dvec4(ndc, d, 1.0);
  rel /= rel.w;
  glm::dvec4 prevClip = session::previousViewProjRelative(v0, v1.position, 1.0) * rel;
  glm::dvec2 expected = (ndc - glm::dvec2(prevClip) / prevClip.w) * 0.5;
  glm::dvec2 got(motion[(y * 64 + x) * 2], motion[(y * 64 + x) * 2 + 1]);
  ASSERT_GT(glm::length(expected), 1e-3);  // the move is visible
  EXPECT_NEAR(got.x, expected.x, 2e-3);
  EXPECT_NEAR(got.y, expected.y, 2e-3);
}

}  // namespace tl::test
