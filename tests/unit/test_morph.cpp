// Morph targets: import of the banners scene (one copy of the shared mesh per node, one
// channel each), weights interpolated between keys and looping, vertices deformed by the
// closed form, conservative bounds, and a bad channel refused with one clear line.
#include "../common/temp_dir.h"
#include "scene/morph.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace tl::scene {
namespace {

using tl::test::contentFile;

namespace fs = std::filesystem;


const Scene& banners() {
  static const Scene scene = loadGltf(contentFile("banners.gltf"));
  return scene;
}

TEST(Morph, BannersImportOneDeformingMeshPerNodeAndOneChannelEach) {
  const Scene& s = banners();
  size_t deforming = 0;
  for (const auto& m : s.meshes) deforming += m.deforms();
  EXPECT_EQ(deforming, 48u);
  EXPECT_EQ(s.morphAnimations.size(), 48u);
  EXPECT_DOUBLE_EQ(s.animationSeconds, 2.0);
  std::vector<int> users(s.meshes.size(), 0);
  for (const auto& inst : s.instances) ++users[inst.mesh];
  for (size_t m = 0; m < s.meshes.size(); ++m)
    EXPECT_TRUE(!s.meshes[m].deforms() || users[m] == 1) << s.meshes[m].name << " has " << users[m] << " instances";
  for (const auto& a : s.morphAnimations) EXPECT_TRUE(s.meshes[a.mesh].deforms());
  EXPECT_TRUE(s.warnings.empty());
}

// A one-mesh scene with one target and a hand-made channel: exact answers.
Scene tiny() {
  Scene s;
  Mesh m;
  m.vertices.resize(2);
  m.vertices[0].position = {0, 0, 0};
  m.vertices[1].position = {1, 0, 0};
  m.vertices[0].normal = m.vertices[1].normal = {0, 1, 0};
  m.indices = {0, 1, 1};
  MorphTarget t;
  t.positions = {{0, 2, 0}, {0, 0, 4}};
  t.normals = {{1, 0, 0}, {0, 0, 0}};
  m.morphTargets = {t};
  m.morphWeights = {0.25f};
  s.meshes.push_back(m);
  s.meshes.push_back(Mesh{});  // a still mesh: no weights
  MorphAnimation a;
  a.mesh = 0;
  a.times = {0.0f, 1.0f, 3.0f};
  a.weights = {0.0f, 1.0f, -1.0f};
  s.morphAnimations.push_back(a);
  s.animationSeconds = 3.0;
  return s;
}

TEST(Morph, WeightsInterpolateBetweenKeysAndLoop) {
  Scene s = tiny();
  EXPECT_FLOAT_EQ(morphWeightsAt(s, 0.5)[0][0], 0.5f);
  EXPECT_FLOAT_EQ(morphWeightsAt(s, 2.0)[0][0], 0.0f);   // halfway from 1 to -1
  EXPECT_FLOAT_EQ(morphWeightsAt(s, 3.5)[0][0], 0.5f);   // loops
  EXPECT_FLOAT_EQ(morphWeightsAt(s, -0.5)[0][0], -0.5f);  // -0.5 s is 2.5 s of the loop
  EXPECT_TRUE(morphWeightsAt(s, 0.5)[1].empty());
  s.morphAnimations[0].step = true;
  EXPECT_FLOAT_EQ(morphWeightsAt(s, 0.9)[0][0], 0.0f);
  s.morphAnimations.clear();
  EXPECT_FLOAT_EQ(morphWeightsAt(s, 0.9)[0][0], 0.25f) << "no channel: the mesh's own weights";
}

TEST(Morph, VerticesFollowTheClosedForm) {
  Scene s = tiny();
  std::vector<Vertex> out;
  deformVertices(s.meshes[0], {0.5f}, out);
  EXPECT_EQ(out[0].position, glm::vec3(0, 1, 0));
  EXPECT_EQ(out[1].position, glm::vec3(1, 0, 2));
  EXPECT_NEAR(glm::length(out[0].normal - glm::normalize(glm::vec3(0.5f, 1, 0))), 0.0f, 1e-6f);
  EXPECT_EQ(out[1].normal, glm::vec3(0, 1, 0));
  Bounds b = morphBounds(s.meshes[0]);
  EXPECT_EQ(b.min, glm::dvec3(0, -2, -4));
  EXPECT_EQ(b.max, glm::dvec3(1, 2, 4));
}

TEST(Morph, AChannelWithTheWrongValueCountIsOneClearError) {
  const fs::path dir = fs::temp_directory_path() / "twinlight-morph-bad";
  fs::create_directories(dir);
  auto j = nlohmann::json::parse(std::ifstream(contentFile("banners.gltf")));
  // The first channel's output accessor claims one value fewer.
  int sampler = j["animations"][0]["channels"][0]["sampler"];
  int output = j["animations"][0]["samplers"][sampler]["output"];
  j["accessors"][output]["count"] = int(j["accessors"][output]["count"]) - 1;
  std::ofstream(dir / "banners.gltf") << j.dump();
  fs::copy_file(contentFile("banners.bin"), dir / "banners.bin", fs::copy_options::overwrite_existing);
  try {
    loadGltf(dir / "banners.gltf");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("banners.gltf"), std::string::npos) << what;
    EXPECT_NE(what.find("morph targets"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tl::scene
