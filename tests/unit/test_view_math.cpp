// Camera and shadow matrices: reversed Z, camera-relative precision far from the origin,
// and a shadow fit that covers what the camera sees.
#include "session/view_math.h"

#include <gtest/gtest.h>

namespace tl::session {
namespace {

glm::dvec3 project(const glm::dmat4& m, const glm::dvec3& p) {
  glm::dvec4 c = m * glm::dvec4(p, 1.0);
  return glm::dvec3(c) / c.w;
}

TEST(ViewMath, ReversedZMapsNearToOneAndFarToZero) {
  View v;
  v.position = glm::dvec3(0.0);
  v.forward = {0, 0, -1};
  v.znear = 0.125f;  // exactly representable, so the near plane lands on 1 exactly
  auto m = cameraMatrices(v, 16.0 / 9.0);
  EXPECT_NEAR(project(m.viewProj, {0, 0, -0.125}).z, 1.0, 1e-12);
  EXPECT_NEAR(project(m.viewProj, {0, 0, -1e9}).z, 0.0, 1e-9);
  EXPECT_GT(project(m.viewProj, {0, 0, -1}).z, project(m.viewProj, {0, 0, -2}).z);
  // Vulkan clip space: +Y world (up) lands at negative y (top of the image).
  EXPECT_LT(project(m.viewProj, {0, 1, -5}).y, 0.0);
}

TEST(ViewMath, CameraRelativeProjectionIsExactFarFromTheOrigin) {
  // The same view 10,000 km from the origin: what reaches the GPU (float, camera-relative)
  // projects a point 0.5 mm beside the axis exactly as it does at the origin.
  for (double far : {0.0, 1e4, 1e7}) {
    View v;
    v.position = glm::dvec3(far, 2.0, far);
    v.forward = glm::normalize(glm::dvec3(0.3, -0.2, -1.0));
    auto m = cameraMatrices(v, 1.0);
    glm::mat4 gpu = glm::mat4(m.viewProj);  // what the shader gets
    glm::dvec3 world = v.position + v.forward * 3.0 + glm::dvec3(0.0005, 0.0, 0.0);
    glm::vec3 relative = glm::vec3(world - v.position);  // what the instance table holds
    glm::vec4 clip = gpu * glm::vec4(relative, 1.0f);
    glm::dvec3 expected = project(m.viewProj, world - v.position);
    EXPECT_NEAR(clip.x / clip.w, expected.x, 1e-6) << far;
    EXPECT_NEAR(clip.y / clip.w, expected.y, 1e-6) << far;
  }
}

TEST(ViewMath, PreviousViewProjectionOfAStillCameraIsTheCurrentOne) {
  View v;
  v.position = {1e6, 5, -3e6};
  v.forward = glm::normalize(glm::dvec3(1, -0.1, 0.2));
  auto cur = cameraMatrices(v, 1.5).viewProj;
  auto prev = previousViewProjRelative(v, v.position, 1.5);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(prev[c][r], cur[c][r], 1e-12);
  // A camera that moved 1 m: a point's previous projection is where it was seen before.
  View moved = v;
  moved.position += glm::dvec3(1, 0, 0);
  glm::dvec3 world = v.position + v.forward * 10.0;
  glm::dvec3 before = project(cur, world - v.position);
  glm::dvec3 viaRelative = project(previousViewProjRelative(v, moved.position, 1.5), world - moved.position);
  EXPECT_NEAR(before.x, viaRelative.x, 1e-9);
  EXPECT_NEAR(before.y, viaRelative.y, 1e-9);
}

TEST(ViewMath, SunShadowFitCoversTheVisibleSceneAndItsCasters) {
  scene::Bounds b;
  b.extend(glm::dvec3(-10, 0, -10));
  b.extend(glm::dvec3(10, 6, 10));
  View v;
  v.position = {0, 3, 13};
  v.forward = glm::normalize(glm::dvec3(0, -0.2, -1));
  glm::dvec3 sun = glm::normalize(glm::dvec3(0.25, -0.55, -0.8));
  SunShadowFit fit = fitSunShadow(v, 16.0 / 9.0, b, sun, 2048);
  EXPECT_GT(fit.texelWorld, 0.0);
  // Every corner of the scene (casters and receivers) is inside the depth range, and every
  // receiver the camera can see lies inside the window.
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 p((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
    glm::dvec3 s = project(fit.viewProj, p - v.position);
    EXPECT_GE(s.z, 0.0);
    EXPECT_LE(s.z, 1.0);
    EXPECT_LE(std::abs(s.x), 1.0 + 1e-9);
    EXPECT_LE(std::abs(s.y), 1.0 + 1e-9);
  }
  // Texel snapping: moving the camera by a fraction of a texel keeps the window's grid.
  View nudged = v;
  nudged.position.x += fit.texelWorld * 0.3;
  SunShadowFit fit2 = fitSunShadow(nudged, 16.0 / 9.0, b, sun, 2048);
  EXPECT_NEAR(fit2.texelWorld, fit.texelWorld, 1e-12);
}

}  // namespace
}  // namespace tl::session

namespace tl::session {
namespace {

TEST(CameraCut, JumpsAndTurnsAreCutsSmallMovesAreNot) {
  View a;
  a.position = {0.0, 1.0, 0.0};
  a.forward = {0.0, 0.0, -1.0};
  View b = a;
  b.position += glm::dvec3(0.5, 0.0, 0.0);
  EXPECT_FALSE(isCameraCut(a, b, 10.0)) << "walking half a metre in a 10 m scene";
  b.position = a.position + glm::dvec3(3.0, 0.0, 0.0);
  EXPECT_TRUE(isCameraCut(a, b, 10.0)) << "jumping 3 m in a 10 m scene";
  b = a;
  b.forward = glm::normalize(glm::dvec3(1.0, 0.0, -1.0));
  EXPECT_FALSE(isCameraCut(a, b, 10.0)) << "turning 45 degrees";
  b.forward = {1.0, 0.0, 0.0};
  EXPECT_TRUE(isCameraCut(a, b, 10.0)) << "turning 90 degrees";
}

}  // namespace
}  // namespace tl::session
