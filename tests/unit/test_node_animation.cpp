// Node TRS animation: channel values between keys against closed forms (lerp, slerp, step,
// the cubic Hermite spline), the loop, parents before children, the moving_door scene as
// imported (hinge and crate at known times, bounds holding every pose, nothing ignored), and
// bad channels refused with one clear line.
#include "../common/edited_content.h"
#include "../common/test_scenes.h"
#include "scene/node_animation.h"

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

glm::dvec3 origin(const glm::dmat4& m) { return glm::dvec3(m[3]); }

// Two nodes: a root that the channels drive and a child 1 m along the root's +x.
Scene twoNodes(NodeAnimation a) {
  Scene s;
  s.nodes.resize(2);
  s.nodes[1].parent = 0;
  s.nodes[1].translation = {1.0, 0.0, 0.0};
  s.animationSeconds = a.times.back();
  s.nodeAnimations.push_back(std::move(a));
  return s;
}

TEST(NodeAnimation, TranslationIsLinearBetweenKeysHeldAtTheEndsAndLoops) {
  NodeAnimation a;
  a.property = NodeProperty::Translation;
  a.times = {1.0f, 3.0f};
  a.values = {{0, 0, 0, 0}, {4, -2, 8, 0}};
  Scene s = twoNodes(a);
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 2.0)), glm::dvec3(2, -1, 4)), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 2.5)), glm::dvec3(3, -1.5, 6)), 0.0, 1e-9);
  // Before the first key: the first key's value (t = 0.5 of the 3 s loop).
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 0.5)), glm::dvec3(0, 0, 0)), 0.0, 1e-9);
  // The loop is 3 s long: 5 s is 2 s.
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 5.0)), glm::dvec3(2, -1, 4)), 0.0, 1e-9);
  // The child follows its parent: 1 m further along x.
  const auto world = nodeWorldTransformsAt(s, 2.0);
  EXPECT_NEAR(glm::distance(origin(world[1]), glm::dvec3(3, -1, 4)), 0.0, 1e-9);
  // STEP holds the key at or before t.
  s.nodeAnimations[0].interpolation = Interpolation::Step;
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 2.9)), glm::dvec3(0, 0, 0)), 0.0, 1e-9);
}

TEST(NodeAnimation, RotationIsSlerpedAndTurnsTheChildAboutTheParent) {
  NodeAnimation a;
  a.property = NodeProperty::Rotation;
  a.times = {0.0f, 2.0f};
  const glm::dquat quarter = glm::angleAxis(kPi / 2, glm::dvec3(0, 1, 0));
  a.values = {{0, 0, 0, 1}, {quarter.x, quarter.y, quarter.z, quarter.w}};
  Scene s = twoNodes(a);
  // Halfway through the keys the root has turned 45 degrees about +Y: the child, 1 m along
  // the root's +x, stands at (cos 45, 0, -sin 45) (a turn about +Y takes +x towards -z).
  const auto world = nodeWorldTransformsAt(s, 1.0);
  const double c = std::sqrt(0.5);
  EXPECT_NEAR(glm::distance(origin(world[1]), glm::dvec3(c, 0, -c)), 0.0, 1e-9);
  // A quarter of the way: 22.5 degrees (slerp is uniform in angle; a normalised lerp is not:
  // it would give 20.7 degrees here).
  const glm::dvec3 p = origin(nodeWorldTransformsAt(s, 0.5)[1]);
  EXPECT_NEAR(std::atan2(-p.z, p.x), kPi / 8, 1e-9);
  // The sign of a key's quaternion does not matter: -q is the same rotation, taken the short way.
  s.nodeAnimations[0].values[1] = -s.nodeAnimations[0].values[1];
  EXPECT_NEAR(glm::distance(origin(nodeWorldTransformsAt(s, 1.0)[1]), glm::dvec3(c, 0, -c)), 0.0, 1e-9);
}

TEST(NodeAnimation, CubicSplineFollowsTheHermiteCurveWithTangentsPerSecond) {
  NodeAnimation a;
  a.property = NodeProperty::Scale;
  a.interpolation = Interpolation::CubicSpline;
  a.times = {0.0f, 2.0f};
  // Keys: (in-tangent, value, out-tangent). Scale x from 1 to 3 with out-tangent 4/s at the
  // first key and in-tangent 0 at the second; y and z stay 1.
  a.values = {{0, 0, 0, 0}, {1, 1, 1, 0}, {4, 0, 0, 0}, {0, 0, 0, 0}, {3, 1, 1, 0}, {0, 0, 0, 0}};
  Scene s = twoNodes(a);
  // p(s) = (2s^3 - 3s^2 + 1) p0 + (s^3 - 2s^2 + s) dt m0 + (-2s^3 + 3s^2) p1 + (s^3 - s^2) dt m1
  // at s = 0.25 (t = 0.5 s), dt = 2: 0.84375 + 0.140625 * 8 + 0.15625 * 3 = 2.4375.
  const glm::dmat4 m = nodeLocalTransformAt(s, 0, 0.5);
  EXPECT_NEAR(glm::length(glm::dvec3(m[0])), 2.4375, 1e-6);
  EXPECT_NEAR(glm::length(glm::dvec3(m[1])), 1.0, 1e-9);
}

TEST(NodeAnimation, AMatrixNodeIsNeverAnimatedAndPosingMovesOnlyAnimatedInstances) {
  NodeAnimation a;
  a.property = NodeProperty::Translation;
  a.times = {0.0f, 1.0f};
  a.values = {{0, 0, 0, 0}, {0, 10, 0, 0}};
  Scene s = twoNodes(a);
  s.nodes.push_back(Node{});  // node 2: still
  Mesh m;
  m.bounds.extend(glm::dvec3(-1));
  m.bounds.extend(glm::dvec3(1));
  s.meshes.push_back(m);
  for (uint32_t n : {1u, 2u}) {
    Instance i;
    i.node = n;
    i.transform = glm::translate(glm::dmat4(1.0), s.nodes[n].translation);
    i.worldBounds = m.bounds;
    s.instances.push_back(i);
  }
  EXPECT_EQ(poseInstances(s, 0.5), 1u);
  EXPECT_NEAR(glm::distance(origin(s.instances[0].transform), glm::dvec3(1, 5, 0)), 0.0, 1e-9);
  EXPECT_NEAR(s.instances[0].worldBounds.min.y, 4.0, 1e-9);
  EXPECT_EQ(poseInstances(s, 0.5), 0u);  // the same pose again moves nothing
  s.nodes[0].matrix = glm::dmat4(1.0);
  EXPECT_NEAR(glm::distance(origin(nodeLocalTransformAt(s, 0, 0.5)), glm::dvec3(0)), 0.0, 1e-12);
}

const Scene& movingDoor() {
  static const Scene scene = loadGltf(contentFile("moving_door.gltf"));
  return scene;
}

TEST(NodeAnimation, MovingDoorImportsTheHingeAndTheCrateWithNothingIgnored) {
  Scene s = movingDoor();
  EXPECT_EQ(s.nodeAnimations.size(), 2u);
  EXPECT_DOUBLE_EQ(s.animationSeconds, 4.0);
  EXPECT_TRUE(s.ignored.empty()) << s.ignored.front();
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  // Closed, the door fills the doorway: its centre at x = 0, 1.0975 m up, mid-wall (z = 0.125).
  poseInstances(s, 0.5);
  EXPECT_NEAR(glm::distance(origin(instanceNamed(s, "door").transform), glm::dvec3(0.0, 1.0975, 0.125)), 0.0, 1e-6);
  // Open (2.5 s), it has turned 90 degrees inwards about the hinge at x = -0.6: its centre is
  // 0.6 m into the room from the hinge.
  poseInstances(s, 2.5);
  EXPECT_NEAR(glm::distance(origin(instanceNamed(s, "door").transform), glm::dvec3(-0.6, 1.0975, 0.125 - 0.6)), 0.0, 1e-6);
  // Halfway through its opening (1.5 s): 45 degrees.
  poseInstances(s, 1.5);
  const double c = 0.6 * std::sqrt(0.5);
  EXPECT_NEAR(glm::distance(origin(instanceNamed(s, "door").transform), glm::dvec3(-0.6 + c, 1.0975, 0.125 - c)), 0.0, 1e-6);
  // The crate: x from -3 at 0 s to +3 at 2 s and back.
  poseInstances(s, 1.0);
  EXPECT_NEAR(glm::distance(origin(instanceNamed(s, "crate").transform), glm::dvec3(0.0, 0.3, 2.5)), 0.0, 1e-6);
  poseInstances(s, 3.5);
  EXPECT_NEAR(origin(instanceNamed(s, "crate").transform).x, -1.5, 1e-6);
  // The scene's bounds hold the crate at both ends of its path.
  EXPECT_LE(s.bounds.min.x, -8.0);
  EXPECT_GE(s.bounds.max.z, 8.0);
  const Scene& file = movingDoor();
  EXPECT_NE(file.contentHash, 0u);
}

TEST(NodeAnimation, BadChannelsAreOneClearError) {
  tl::test::expectEachEditIsOneClearError(
      "moving_door",
      {
          {"a node that does not exist", [](auto& j) { j["animations"][0]["channels"][0]["target"]["node"] = 999; },
           "drives node 999, which does not exist"},
          {"one value fewer than keys",
           [](auto& j) {
             int sampler = j["animations"][0]["channels"][0]["sampler"];
             int output = j["animations"][0]["samplers"][sampler]["output"];
             j["accessors"][output]["count"] = int(j["accessors"][output]["count"]) - 1;
           },
           "values for 5 keys"},
          {"a rotation given as three numbers",
           [](auto& j) {
             int sampler = j["animations"][0]["channels"][0]["sampler"];
             int output = j["animations"][0]["samplers"][sampler]["output"];
             j["accessors"][output]["type"] = "VEC3";
           },
           "expected 4"},
      });
}

// A channel of a node given as a matrix is not played, and the report says so.
TEST(NodeAnimation, AMatrixNodesChannelIsReportedNotPlayed) {
  tl::test::TempDir dir("twinlight-node-animation-matrix");
  const Scene s = tl::test::loadEditedContent(dir.path, "moving_door", [](nlohmann::json& j) {
    const int hinge = j["animations"][0]["channels"][0]["target"]["node"];
    auto& node = j["nodes"][hinge];
    const double hx = node["translation"][0], hz = node["translation"][2];
    node.erase("translation");
    node["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, hx, 0, hz, 1};
  });
  ASSERT_EQ(s.ignored.size(), 1u);
  EXPECT_NE(s.ignored[0].find("animation of a node given as a matrix"), std::string::npos) << s.ignored[0];
  EXPECT_EQ(s.nodeAnimations.size(), 1u);  // the crate's
}

}  // namespace
}  // namespace tl::scene
