// Skinned meshes in every path: content/walker.gltf, a box figure whose legs and arms
// swing on five joints while it walks. The rasterizing paths draw the skinned vertices; the
// reference traces them (its bottom level rebuilt exactly); the rt path refits its bottom level.
#include "gpu_fixture.h"
#include "../common/test_scenes.h"

#include "lighting/common/composite_pass.h"

#include <algorithm>
#include <cmath>

namespace tl::test {
namespace {

using lighting::kCompositeHdr;

// Looks down at the walker from the front, above, following its root (x = -2 + t m), so the
// ground is behind it everywhere and only the pose changes between times.
void lookAtWalker(session::Session& s, double seconds) {
  session::View v = s.view();
  const double x = -2.0 + seconds;
  v.position = {x, 2.2, 3.0};
  v.forward = glm::normalize(glm::dvec3(x, 0.7, 0.0) - v.position);
  v.up = {0.0, 1.0, 0.0};
  v.yfovRadians = 0.87f;
  s.setView(v);
}

// Pixels showing the walker's blue cloth (b > 2.5 r: the grey ground is at most 1.7 in the
// sky-lit shadow, the cloth 3.5 in sunlight and more in shade).
std::vector<uint8_t> clothMask(const std::vector<float>& rgba) {
  std::vector<uint8_t> mask(rgba.size() / 4);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = rgba[4 * i + 2] > 2.5f * rgba[4 * i] && rgba[4 * i + 2] > 0.0f;
  return mask;
}

double intersectionOverUnion(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t both = 0, either = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    both += a[i] && b[i];
    either += a[i] || b[i];
  }
  return either ? double(both) / double(either) : 1.0;
}

class SkinningTest : public RayTracingTest {};

// The G-buffer's instance ids say where the raster drew the skinned body, at a pose where the
// legs are spread (0.25 s) and one where they hang straight (0.5 s). Every path's image shows
// the cloth there: its pixels against the ids of the same pose (IoU over 0.8; the reference's
// jittered primary rays soften the small figure's edges) and clearly closer to them than to the
// other pose's (by 0.2; the two silhouettes' own IoU is about 0.5).
TEST_F(SkinningTest, EveryPathShowsTheWalkersPose) {
  auto& s = session();
  s.loadScene(contentFile("walker.gltf"));
  constexpr uint32_t kWidth = 128, kHeight = 96;
  s.setSize(kWidth, kHeight);
  const uint32_t body = instanceIdOf(s.scene(), "walker_body");
  const double times[2] = {0.25, 0.5};
  std::vector<uint8_t> silhouette[2];
  for (int pose = 0; pose < 2; ++pose) {
    lookAtWalker(s, times[pose]);
    s.setAnimationTime(times[pose]);
    s.setPath("direct");
    s.requestBuffer("gbuffer.instanceId");
    s.renderFrames(1);
    const auto ids = s.buffer("gbuffer.instanceId");
    const auto* id = reinterpret_cast<const uint32_t*>(ids.bytes.data());
    silhouette[pose].resize(size_t(kWidth) * kHeight);
    for (size_t i = 0; i < silhouette[pose].size(); ++i) silhouette[pose][i] = id[i] == body;
  }
  const double between = intersectionOverUnion(silhouette[0], silhouette[1]);
  std::printf("walker silhouettes at 0.25 s and 0.5 s: IoU %.3f\n", between);
  ASSERT_LT(between, 0.7) << "the poses must differ for the comparison to mean anything";
  for (int pose = 0; pose < 2; ++pose) {
    // The view follows the root: both poses are seen from the same place relative to it.
    lookAtWalker(s, times[pose]);
    s.setAnimationTime(times[pose]);
    for (const char* path : {"direct", "legacy", "rt", "reference"}) {
      s.setPath(path);
      s.resetHistory();
      s.requestBuffer(std::string(kCompositeHdr));
      s.renderFrames(std::string(path) == "reference" ? 16 : 4);
      const auto cloth = clothMask(s.buffer(std::string(kCompositeHdr)).texels());
      const double same = intersectionOverUnion(cloth, silhouette[pose]), other = intersectionOverUnion(cloth, silhouette[1 - pose]);
      std::printf("walker at %.2f s, %s: cloth against the raster's silhouette IoU %.3f, against the other pose's %.3f\n",
                  times[pose], path, same, other);
      EXPECT_GT(same, 0.8) << path << " at " << times[pose] << " s";
      EXPECT_GT(same, other + 0.2) << path << " at " << times[pose] << " s";
    }
  }
}

// The rt path refits the skinned body's bottom level when the pose changes (the deforming-mesh
// throttle), and the reference's image after animating to a time equals a fresh load's at it.
TEST_F(SkinningTest, RayTracedLevelsFollowTheSkinnedPose) {
  auto& s = session();
  auto figure = [&](const char* name) { return pathFigure(s, name); };
  s.loadScene(contentFile("walker.gltf"));
  s.setSize(48, 36);
  lookAtWalker(s, 0.25);
  s.setPath("rt");
  s.setAnimationTime(0.0);
  s.renderFrames(1);
  EXPECT_EQ(figure("deformingMeshes"), 1.0);
  s.setAnimationTime(0.25);
  s.renderFrames(1);
  EXPECT_EQ(figure("blasRefits"), 1.0) << "the moved pose is refitted at once (the throttle picks 16 a frame)";

  auto reference = [&] {
    s.setPath("reference");
    s.setFrameIndex(0);
    s.resetHistory();
    s.requestBuffer("reference.radiance");
    s.renderFrames(8);
    return s.buffer("reference.radiance").texels();
  };
  s.setAnimationTime(0.5);
  const auto straight = reference();
  s.setAnimationTime(0.25);
  const auto animated = reference();
  s.loadScene(contentFile("walker.gltf"));
  s.setSize(48, 36);
  lookAtWalker(s, 0.25);
  s.setAnimationTime(0.25);
  const auto loaded = reference();
  const double same = relativeDifferenceRgb(animated, loaded), other = relativeDifferenceRgb(straight, loaded);
  std::printf("reference on the walker at 0.25 s: animated there vs loaded there %.2e, the 0.5 s pose vs it %.2e\n", same,
              other);
  EXPECT_LT(same, 1e-4);
  EXPECT_GT(other, 100.0 * std::max(same, 1e-6));
}

}  // namespace
}  // namespace tl::test
