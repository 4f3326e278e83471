// The project's interiors (content/doorway_room, slit_corridor, twin_rooms): each renders
// in every lighting path without a validation message or a non-finite value, and the closed
// room of twin_rooms is black in the reference (its true image) while the sunlit room beside it
// is not. Cheap sizes: the figures of these scenes are measured by `twinlight compare`
// (docs/accuracy.md), not here.
#include "gpu_fixture.h"

#include "shared/common.h"

namespace tl::test {
namespace {

using InteriorsTest = RayTracingTest;

// Mean luminance of an RGBA float read-back, and its count of non-finite or negative texels.
struct Stats {
  double mean = 0.0;
  size_t bad = 0;
};
Stats stats(const graph::Readback& rb) {
  const auto t = rb.texels();
  Stats s;
  for (size_t i = 0; i + 3 < t.size(); i += 4) {
    const glm::vec3 c(t[i], t[i + 1], t[i + 2]);
    if (!std::isfinite(c.x + c.y + c.z) || glm::min(c.x, glm::min(c.y, c.z)) < 0.0f) {
      ++s.bad;
      continue;
    }
    s.mean += shared::tlLuminance(c);
  }
  s.mean /= double(t.size() / 4);
  return s;
}

// The composite's HDR image (or the reference's radiance) after `frames` frames of `path`.
Stats render(session::Session& s, const std::string& path, uint32_t frames) {
  s.setPath(path);
  s.setSize(64, 48);
  s.settings().referenceSamplesPerFrame = 16;
  s.resetHistory();
  const std::string image = path == "reference" ? "reference.radiance" : "composite.hdr";
  s.requestBuffer(image);
  s.renderFrames(frames);
  return stats(s.buffer(image));
}

TEST_F(InteriorsTest, EachRendersInEveryPath) {
  auto& s = session();
  for (const char* scene : {"doorway_room.gltf", "slit_corridor.gltf", "twin_rooms.gltf"}) {
    s.loadScene(contentFile(scene));
    for (const char* path : {"direct", "legacy", "rt", "reference"}) {
      const Stats st = render(s, path, 2);
      std::printf("%-20s %-9s mean %.4f\n", scene, path, st.mean);
      EXPECT_EQ(st.bad, 0u) << scene << " " << path;
      // Camera 0 of each sees lit surfaces (bounce light at least): every path but direct,
      // which has no bounce light, shows something.
      if (std::string(path) != "direct") {
        EXPECT_GT(st.mean, 0.0) << scene << " " << path;
      }
    }
  }
}

// twin_rooms: camera 0 in the sunlit room, camera 1 in the closed room beside it (walls 0.25 m,
// 1.8 of the legacy path's finest voxels). No light can reach the closed room.
TEST_F(InteriorsTest, ClosedRoomIsBlackInTheReference) {
  auto& s = session();
  s.loadScene(contentFile("twin_rooms.gltf"));
  s.useSceneCamera(0);
  const Stats lit = render(s, "reference", 2);
  s.useSceneCamera(1);
  const Stats closed = render(s, "reference", 2);
  std::printf("twin_rooms reference: lit room mean %.5f, closed room mean %.3g\n", lit.mean, closed.mean);
  EXPECT_GT(lit.mean, 0.05);
  EXPECT_LT(closed.mean, 1e-4 * lit.mean);
  EXPECT_EQ(lit.bad + closed.bad, 0u);
}

}  // namespace
}  // namespace tl::test
