// Skinning: joint matrices and linear blend skinning against closed forms (a two-joint bar bent
// 90 degrees), the skinned mesh's node transform ignored as glTF says, the walker as imported
// (one skin, five joints, the left foot where the swung leg puts it, bounds holding every
// pose) and bad skins refused with one clear line.
#include "../common/edited_content.h"
#include "../common/test_scenes.h"
#include "scene/node_animation.h"
#include "scene/skinning.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>

namespace tl::scene {
namespace {

using tl::test::contentFile;
using tl::test::instanceNamed;

constexpr double kPi = 3.14159265358979323846;

// Joint 0 at the origin, joint 1 one metre along x (its child); a mesh of three vertices at
// x = 2: bound to joint 1, half to each, and to joint 0.
struct Bar {
  Scene scene;
  Mesh mesh;
  Bar() {
    scene.nodes.resize(2);
    scene.nodes[1].parent = 0;
    scene.nodes[1].translation = {1.0, 0.0, 0.0};
    Skin skin;
    skin.joints = {0, 1};
    skin.inverseBind = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), glm::dvec3(-1.0, 0.0, 0.0))};
    scene.skins.push_back(skin);
    mesh.vertices.resize(3);
    for (auto& v : mesh.vertices) {
      v.position = {2.0f, 0.0f, 0.0f};
      v.normal = {1.0f, 0.0f, 0.0f};
    }
    mesh.joints = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}};
    mesh.weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};
    mesh.skin = 0;
  }
  std::vector<Vertex> posed(const glm::dmat4& meshNodeWorld = glm::dmat4(1.0)) const {
    std::vector<Vertex> v = mesh.vertices;
    skinVertices(mesh, jointMatrices(scene.skins[0], meshNodeWorld, nodeWorldTransformsAt(scene, 0.0)), v);
    return v;
  }
};

double distance(glm::vec3 a, glm::dvec3 b) { return glm::distance(glm::dvec3(a), b); }

TEST(Skinning, TheBindPoseLeavesVerticesWhereTheyAre) {
  const Bar bar;
  for (const Vertex& v : bar.posed()) EXPECT_NEAR(distance(v.position, {2, 0, 0}), 0.0, 1e-6);
}

TEST(Skinning, ABentJointMovesItsVerticesAndBlendsHalfWeights) {
  Bar bar;
  bar.scene.nodes[1].rotation = glm::angleAxis(kPi / 2, glm::dvec3(0, 0, 1));
  const auto v = bar.posed();
  // Bound to joint 1: one metre past it along its x, which now points along +y.
  EXPECT_NEAR(distance(v[0].position, {1, 1, 0}), 0.0, 1e-6);
  EXPECT_NEAR(distance(v[0].normal, {0, 1, 0}), 0.0, 1e-6);
  // Half and half: the mean of both joints' results (linear blend skinning).
  EXPECT_NEAR(distance(v[1].position, {1.5, 0.5, 0}), 0.0, 1e-6);
  EXPECT_NEAR(distance(v[1].normal, glm::normalize(glm::dvec3(1, 1, 0))), 0.0, 1e-6);
  // Bound to joint 0, which did not move.
  EXPECT_NEAR(distance(v[2].position, {2, 0, 0}), 0.0, 1e-6);
}

TEST(Skinning, TheMeshNodesOwnTransformIsIgnored) {
  Bar bar;
  bar.scene.nodes[1].rotation = glm::angleAxis(kPi / 2, glm::dvec3(0, 0, 1));
  // The instance applies its node's transform after skinning; glTF says the result is the
  // joints' alone: the two cancel.
  const glm::dmat4 meshNode = glm::translate(glm::dmat4(1.0), glm::dvec3(5, -3, 2)) *
                              glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0, 1, 0));
  const auto v = bar.posed(meshNode);
  const glm::dvec3 world = glm::dvec3(meshNode * glm::dvec4(glm::dvec3(v[0].position), 1.0));
  EXPECT_NEAR(glm::distance(world, glm::dvec3(1, 1, 0)), 0.0, 1e-5);
}

const Scene& walker() {
  static const Scene scene = loadGltf(contentFile("walker.gltf"));
  return scene;
}

// The walker's vertices in world space at `seconds`, as the session poses them.
std::vector<glm::dvec3> walkerAt(const Scene& s, double seconds) {
  const Instance& body = instanceNamed(s, "walker_body");
  const Mesh& mesh = s.meshes[body.mesh];
  const auto world = nodeWorldTransformsAt(s, seconds);
  std::vector<Vertex> v = mesh.vertices;
  skinVertices(mesh, jointMatrices(s.skins[size_t(mesh.skin)], world[body.node], world), v);
  std::vector<glm::dvec3> out;
  for (const Vertex& x : v) out.push_back(glm::dvec3(world[body.node] * glm::dvec4(glm::dvec3(x.position), 1.0)));
  return out;
}

TEST(Skinning, WalkerImportsOneSkinOfFiveJointsWithNothingIgnored) {
  const Scene& s = walker();
  ASSERT_EQ(s.skins.size(), 1u);
  EXPECT_EQ(s.skins[0].joints.size(), 5u);
  EXPECT_EQ(s.nodeAnimations.size(), 5u);
  EXPECT_DOUBLE_EQ(s.animationSeconds, 4.0);
  EXPECT_TRUE(s.ignored.empty()) << s.ignored.front();
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const Mesh& mesh = s.meshes[instanceNamed(s, "walker_body").mesh];
  EXPECT_TRUE(mesh.skinned());
  EXPECT_TRUE(mesh.deforms());
  ASSERT_EQ(mesh.weights.size(), mesh.vertices.size());
  for (const auto& w : mesh.weights) EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f);
}

// At 0.25 s the left leg has swung 30 degrees forward about its hip joint (0, 0.95, 0.1) and the
// root has walked to x = -1.75: the leg's front lower corner (bind pose (0.07, 0, 0.17), bound
// to the leg alone) is at the root + the hip + R(30) (0.07, -0.95, 0.07).
TEST(Skinning, WalkersFootIsWhereTheSwungLegPutsIt) {
  const Scene& s = walker();
  const Mesh& mesh = s.meshes[instanceNamed(s, "walker_body").mesh];
  size_t corner = mesh.vertices.size();
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    if (glm::distance(mesh.vertices[v].position, glm::vec3(0.07f, 0.0f, 0.17f)) < 1e-5f && mesh.weights[v].x == 1.0f)
      corner = v;
  ASSERT_LT(corner, mesh.vertices.size()) << "the left leg's front lower corner";
  const double a = kPi / 6;
  const glm::dvec3 expected = glm::dvec3(-1.75, 0.95, 0.1) +
                              glm::dvec3(0.07 * std::cos(a) + 0.95 * std::sin(a), 0.07 * std::sin(a) - 0.95 * std::cos(a), 0.07);
  EXPECT_NEAR(glm::distance(walkerAt(s, 0.25)[corner], expected), 0.0, 1e-5);
}

TEST(Skinning, WalkerBoundsHoldEveryPose) {
  const Scene& s = walker();
  for (int k = 0; k <= 64; ++k) {
    const double t = 4.0 * k / 64.0 + 0.01;
    for (const glm::dvec3& p : walkerAt(s, t))
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(p[c], s.bounds.min[c] - 1e-4) << "t " << t;
        EXPECT_LE(p[c], s.bounds.max[c] + 1e-4) << "t " << t;
      }
  }
}

TEST(Skinning, BadSkinsAreOneClearError) {
  tl::test::expectEachEditIsOneClearError(
      "walker",
      {
          {"a joint that is not a node", [](auto& j) { j["skins"][0]["joints"][0] = 999; },
           "has joint node 999, which does not exist"},
          {"fewer joints than the mesh names",
           [](auto& j) { j["skins"][0]["joints"].erase(j["skins"][0]["joints"].size() - 1); },
           "names joint 4 of skin 0, which has 4"},
          {"fewer inverse bind matrices than joints",
           [](auto& j) {
             int a = j["skins"][0]["inverseBindMatrices"];
             j["accessors"][a]["count"] = 3;
           },
           "has 3 inverse bind matrices for 5 joints"},
          {"a skin that does not exist",
           [](auto& j) {
             for (auto& n : j["nodes"])
               if (n.contains("skin")) n["skin"] = 7;
           },
           "refers to skin 7, which does not exist"},
      });
}

}  // namespace
}  // namespace tl::scene
