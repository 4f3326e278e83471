// Motion vectors of deforming meshes: a morph target slides a cube's vertices along +x
// while its instance stands still. The G-buffer's motion on the cube is the vertices' own
// displacement projected (closed form), and zero again once the animation stops.
#include "gpu_fixture.h"
#include "../common/test_scenes.h"

#include <cmath>

namespace tl::test {
namespace {

constexpr uint32_t kWidth = 128, kHeight = 96;

// A unit cube whose one morph target moves every vertex 0.3 m along +x, its weight animated
// from 0 at 0 s to 1 at 1 s: 0.3 m a second.
std::unique_ptr<scene::Scene> slidingCube() {
  scene::Material grey;
  grey.baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  grey.metallic = 0.0f;
  auto s = makeCubeScene(grey);
  scene::Mesh& mesh = s->meshes[0];
  scene::MorphTarget slide;
  slide.positions.assign(mesh.vertices.size(), glm::vec3(0.3f, 0.0f, 0.0f));
  slide.normals.assign(mesh.vertices.size(), glm::vec3(0.0f));
  mesh.morphTargets = {slide};
  mesh.morphWeights = {0.0f};
  mesh.bounds.max.x += 0.3;
  s->instances[0].worldBounds = mesh.bounds;
  s->bounds = mesh.bounds;
  scene::MorphAnimation a;
  a.mesh = 0;
  a.times = {0.0f, 1.0f};
  a.weights = {0.0f, 1.0f};
  s->morphAnimations = {a};
  s->animationSeconds = 1.0;
  return s;
}

struct Motion {
  size_t pixels = 0;  // on the cube
  double meanX = 0.0, worstY = 0.0;
};

Motion cubeMotion(session::Session& s) {
  const auto motion = s.buffer("gbuffer.motion").texels();
  const auto ids = s.buffer("gbuffer.instanceId");
  const auto* id = reinterpret_cast<const uint32_t*>(ids.bytes.data());
  Motion m;
  for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
    if (id[i] != 1) continue;
    ++m.pixels;
    m.meanX += motion[2 * i];
    m.worstY = std::max(m.worstY, std::abs(double(motion[2 * i + 1])));
  }
  if (m.pixels) m.meanX /= double(m.pixels);
  return m;
}

TEST_F(GpuTest, DeformingMeshesMotionVectorsCarryTheirVerticesMotion) {
  auto& s = session();
  s.installScene(slidingCube());
  s.setSize(kWidth, kHeight);
  session::View v = s.view();
  v.position = {0.15, 0.0, 3.0};  // straight at the cube's front face (z = 0.5), 2.5 m away
  v.forward = {0.0, 0.0, -1.0};
  v.up = {0.0, 1.0, 0.0};
  v.yfovRadians = 0.8f;
  s.setView(v);
  constexpr double kStep = 1.0 / 30.0;
  s.setAnimationTime(0.3);
  s.setAnimationStep(kStep);
  s.requestBuffer("gbuffer.motion");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(3);
  const Motion moving = cubeMotion(s);
  // 0.3 m/s x 1/30 s = 1 cm a frame at 2.5 m: in UV, 0.01 / (2 * 2.5 * tan(fov / 2) * aspect).
  const double expected = 0.01 / (2.0 * 2.5 * std::tan(0.4) * (double(kWidth) / kHeight));
  std::printf("morphing cube: %zu px, motion %.6f uv a frame (closed form %.6f), worst |y| %.2e\n", moving.pixels,
              moving.meanX, expected, moving.worstY);
  ASSERT_GT(moving.pixels, 500u);
  EXPECT_NEAR(moving.meanX, expected, 0.03 * expected);
  EXPECT_LT(moving.worstY, 0.05 * expected);

  // The animation stops: one frame later the cube stands still and its motion is zero.
  s.setAnimationStep(0.0);
  s.requestBuffer("gbuffer.motion");
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(2);
  const Motion still = cubeMotion(s);
  std::printf("morphing cube stopped: motion %.2e\n", still.meanX);
  EXPECT_LT(std::abs(still.meanX), 1e-6);
}

}  // namespace
}  // namespace tl::test
