// The legacy path's voxel GI against the two failures voxel cone tracing is known for:
// light leaking through a wall into a closed room, and voxel-sized steps on flat walls.
// The scene: a sunlit room open to the sky beside a closed room, the wall between them
// thicker than one finest voxel, the sun shining on that wall's lit side.
#include "lighting_checks.h"
#include "../common/test_scenes.h"

#include "lighting/common/composite_pass.h"
#include "lighting/legacy/legacy_path.h"
#include "shared/color.h"
#include "shared/packing.h"

#include <algorithm>

namespace tl::test {
namespace {

using namespace lighting;

// Wall thickness: above the finest voxel at the default resolution (checked in the tests).
constexpr float kWall = 0.14f;
// Interiors: the lit room x in [-4, 0], the closed room x in [kWall, 4 + kWall], both
// z in [-2, 2], y in [0, 3]. Only the closed room has a roof.
std::unique_ptr<scene::Scene> makeTwoRooms() {
  scene::Material white;
  white.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  white.metallic = 0.0f;
  white.roughness = 1.0f;
  const float T = kWall, x0 = -4.0f - T, x1 = 4.0f + 2.0f * T;
  auto s = makeBoxesScene(white, {
                                     {{x0, -T, -2.0f - T}, {x1, 0.0f, 2.0f + T}},        // floor
                                     {{x0, 0.0f, -2.0f - T}, {x1, 3.0f, -2.0f}},         // back wall (-z)
                                     {{x0, 0.0f, 2.0f}, {x1, 3.0f, 2.0f + T}},           // front wall (+z)
                                     {{x0, 0.0f, -2.0f}, {-4.0f, 3.0f, 2.0f}},           // lit room's far wall
                                     {{0.0f, 0.0f, -2.0f}, {T, 3.0f, 2.0f}},             // the shared wall
                                     {{4.0f + T, 0.0f, -2.0f}, {x1, 3.0f, 2.0f}},        // closed room's far wall
                                     {{0.0f, 3.0f, -2.0f - T}, {x1, 3.0f + T, 2.0f + T}},  // closed room's roof
                                 });
  s->name = "two_rooms";
  return s;
}

// The sun travels towards +x and down: it lights the shared wall's lit side (normal -x).
void lightTwoRooms(session::Session& s) {
  session::Lighting l = s.lighting();
  l.sunDirection = glm::normalize(glm::dvec3(0.6, -1.0, 0.25));
  l.sunIrradiance = glm::vec3(20.0f);
  l.skyRadiance = glm::vec3(1.0f);
  s.setLighting(l);
}

class LegacyLeakTest : public GpuTest {
 protected:
  void look(glm::dvec3 position, glm::dvec3 forward, float fov = 1.3f) {
    auto& s = session();
    session::View v = s.view();
    v.position = position;
    v.forward = glm::normalize(forward);
    v.up = {0.0, 1.0, 0.0};
    v.yfovRadians = fov;
    s.setView(v);
  }
  // Mean luminance of an RGB(A) buffer over every pixel.
  double meanLuminance(const std::string& name) {
    const auto& b = session().buffer(name);
    auto t = b.texels();
    const uint32_t c = b.channels();
    double sum = 0.0;
    const size_t n = t.size() / c;
    for (size_t i = 0; i < n; ++i) sum += shared::tlLuminance(glm::vec3(t[c * i], t[c * i + 1], t[c * i + 2]));
    return sum / double(n);
  }
};

// The lit room first, so the voxels hold its light (and, through the screen, its bounces),
// then the closed room from inside; the truth there is black. Measured on lavapipe: closed
// room 10.4 % of the lit room's mean. The goal (under 1 %) is NOT met: docs/accuracy.md,
// "Light leaking into closed rooms", lists what was tried and what each did. The bound keeps
// it from getting worse.
TEST_F(LegacyLeakTest, ClosedRoomBesideASunlitOneLeakIsBounded) {
  auto& s = session();
  auto scene = makeTwoRooms();
  const LegacyClipmapFit fit = fitLegacyClipmap(scene->bounds, glm::dvec3(0.0), s.settings().legacyVoxelResolution,
                                                s.settings().legacyLevel0Extent, s.settings().legacyMaxLevels);
  ASSERT_GE(kWall, fit.clipmap.levelMin[0].w) << "the walls must be at least one finest voxel thick";
  s.installScene(std::move(scene));
  lightTwoRooms(s);
  s.setPath("legacy");
  s.setSize(64, 48);
  s.requestBuffer(kCompositeHdr);
  look({-3.6, 1.5, 0.0}, {1.0, -0.1, 0.0});
  s.renderFrames(8);
  const double lit = meanLuminance(kCompositeHdr);
  look({3.6 + kWall, 1.5, 0.0}, {-1.0, -0.1, 0.0});
  s.renderFrames(8);
  const double closed = meanLuminance(kCompositeHdr);
  RecordProperty("lit_room_mean", std::to_string(lit));
  RecordProperty("closed_room_mean", std::to_string(closed));
  std::printf("two rooms: lit room %.5f, closed room %.5f, ratio %.5f\n", lit, closed, closed / lit);
  ASSERT_GT(lit, 0.1);
  EXPECT_LT(closed, 0.12 * lit) << "closed " << closed << " lit " << lit;
}

// The same on the project's content/twin_rooms.gltf (walls 1.8 finest voxels thick, the lit
// room lit through a doorway, so far dimmer than the room above): camera 0 in the lit room,
// camera 1 in the closed one. Measured: 48.0 %; the goal (1 %) is not met (see above).
TEST_F(LegacyLeakTest, TwinRoomsClosedRoomLeakIsBounded) {
  auto& s = session();
  s.loadScene(contentFile("twin_rooms.gltf"));
  s.setPath("legacy");
  s.setSize(64, 48);
  s.requestBuffer(kCompositeHdr);
  s.useSceneCamera(0);
  s.renderFrames(8);
  const double lit = meanLuminance(kCompositeHdr);
  s.useSceneCamera(1);
  s.renderFrames(8);
  const double closed = meanLuminance(kCompositeHdr);
  RecordProperty("lit_room_mean", std::to_string(lit));
  RecordProperty("closed_room_mean", std::to_string(closed));
  std::printf("twin_rooms: lit room %.5f, closed room %.5f, ratio %.5f\n", lit, closed, closed / lit);
  ASSERT_GT(lit, 0.01);
  EXPECT_LT(closed, 0.55 * lit) << "closed " << closed << " lit " << lit;
}

// Voxel-sized steps. The criterion: along every row and column of a flat wall's pixels, the
// jump between two neighbours less the mean of the jumps either side of it, relative to the
// two pixels' mean: zero on a smooth ramp, a step's height at a step. No step may exceed 2 %
// of the local mean (about the contrast the eye resolves on a flat field).
struct StepContrast {
  double worst = 0.0, p99 = 0.0;
  size_t pairs = 0;
};
StepContrast stepContrast(const std::vector<float>& image, uint32_t channels, const std::vector<bool>& wall, uint32_t w,
                          uint32_t h) {
  auto lum = [&](uint32_t x, uint32_t y) {
    const size_t i = (size_t(y) * w + x) * channels;
    return double(shared::tlLuminance(glm::vec3(image[i], image[i + 1], image[i + 2])));
  };
  std::vector<double> steps;
  for (int dir = 0; dir < 2; ++dir)  // rows, then columns
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        auto at = [&](int k, double& v) {
          const int px = int(x) + (dir == 0 ? k : 0), py = int(y) + (dir == 1 ? k : 0);
          if (px < 0 || py < 0 || px >= int(w) || py >= int(h) || !wall[size_t(py) * w + px]) return false;
          v = lum(uint32_t(px), uint32_t(py));
          return true;
        };
        double a, b, lo, hi;
        if (!at(0, a) || !at(1, b) || !at(-1, lo) || !at(2, hi)) continue;
        // The jump from a to b against the mean of its neighbours' jumps: zero on any
        // smooth ramp whose slope changes slowly, the step's height at a step.
        const double slope = 0.5 * ((a - lo) + (hi - b)), mean = 0.5 * (a + b);
        if (mean <= 0.0) continue;
        steps.push_back(std::abs((b - a) - slope) / mean);
      }
  StepContrast c;
  c.pairs = steps.size();
  if (steps.empty()) return c;
  std::sort(steps.begin(), steps.end());
  c.worst = steps.back();
  c.p99 = steps[size_t(0.99 * double(steps.size() - 1))];
  return c;
}

// The criterion sees a step: a 3 % step in a ramp reads 3 %, the ramp alone 0.
TEST(LegacyStepContrast, MeasuresAStepAndIgnoresARamp) {
  const uint32_t w = 32, h = 4;
  std::vector<float> ramp(size_t(w) * h * 4), stepped;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t c = 0; c < 4; ++c) ramp[(size_t(y) * w + x) * 4 + c] = 1.0f + 0.01f * float(x);
  stepped = ramp;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 16; x < w; ++x)
      for (uint32_t c = 0; c < 4; ++c) stepped[(size_t(y) * w + x) * 4 + c] *= 1.03f;
  const std::vector<bool> all(size_t(w) * h, true);
  EXPECT_LT(stepContrast(ramp, 4, all, w, h).worst, 1e-5);
  EXPECT_NEAR(stepContrast(stepped, 4, all, w, h).worst, 0.03, 0.002);
}

// The step contrast of `image` over the flat middle of the wall whose normal is `wallNormal`
// (x only), seen from `position` along `forward` at 128x96 after 8 frames: wall pixels at
// least 12 pixels (~0.4 m, 3 voxels) from the wall's edges, away from the corners' darkening
// (a gradient, not a step).
StepContrast wallStepContrast(session::Session& s, glm::dvec3 position, glm::dvec3 forward, float wallNormal,
                              const char* image) {
  s.installScene(makeTwoRooms());
  lightTwoRooms(s);
  s.setPath("legacy");
  const uint32_t w = 128, h = 96;
  s.setSize(w, h);
  s.requestBuffer(image);
  s.requestBuffer("gbuffer.normal");
  session::View v = s.view();
  v.position = position;
  v.forward = glm::normalize(forward);
  v.up = {0.0, 1.0, 0.0};
  v.yfovRadians = 1.0f;
  s.setView(v);
  s.renderFrames(8);
  auto n = s.buffer("gbuffer.normal").texels();
  constexpr int kMargin = 12;
  std::vector<bool> facing(size_t(w) * h), wall(size_t(w) * h);
  for (size_t i = 0; i < facing.size(); ++i)
    facing[i] = shared::tlOctDecode(glm::vec2(n[2 * i], n[2 * i + 1])).x * wallNormal > 0.99f;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      bool all = true;
      for (int dy = -kMargin; dy <= kMargin && all; ++dy)
        for (int dx = -kMargin; dx <= kMargin && all; ++dx) {
          const int px = int(x) + dx, py = int(y) + dy;
          all = px >= 0 && py >= 0 && px < int(w) && py < int(h) && facing[size_t(py) * w + px];
        }
      wall[size_t(y) * w + x] = all;
    }
  const auto& b = s.buffer(image);
  StepContrast c = stepContrast(b.texels(), b.channels(), wall, w, h);
  std::printf("%s step contrast: worst %.4f, 99th percentile %.4f over %zu pairs\n", image, c.worst, c.p99, c.pairs);
  EXPECT_GT(c.pairs, size_t(w * h / 3)) << "the camera should see the wall";
  return c;
}

// The lit room's far wall (x = -4, facing +x) is flat and gets no sun, only sky and bounce
// light, so the truth on it is smooth and GI is all of its light; a voxel is ~3.4 pixels
// here. Measured: worst step 0.91 %, 99th percentile 0.39 %.
TEST_F(LegacyLeakTest, NoVoxelSizedStepsOnAFlatWall) {
  const StepContrast c = wallStepContrast(session(), {-0.6, 1.5, 0.0}, {-1.0, 0.0, 0.0}, 1.0f, kCompositeHdr);
  RecordProperty("step_contrast_worst", std::to_string(c.worst));
  RecordProperty("step_contrast_p99", std::to_string(c.p99));
  EXPECT_LT(c.worst, 0.02);
}

// The shared wall's sunlit side (x = 0, facing -x), its half at z > 0 seen from 1.5 m (a
// voxel ~8 pixels): a flat lit wall. The sun (E = 20) is most of its light and would hide the
// GI's steps, so the criterion reads the composite's irradiance without the sun (sky and
// bounce: all the GI), where a step is the GI's own. Measured: worst step 0.59 %, 99th
// percentile 0.38 %; cones whose samples snap to texel centres along each face's axis (tried
// against the leak, docs/accuracy.md) show 7.5 % here and 4.6 % on the far wall.
TEST_F(LegacyLeakTest, NoVoxelSizedStepsOnASunlitWall) {
  const StepContrast c = wallStepContrast(session(), {-1.5, 1.5, 0.9}, {1.0, 0.0, 0.0}, -1.0f, kCompositeIrradiance);
  RecordProperty("step_contrast_worst", std::to_string(c.worst));
  RecordProperty("step_contrast_p99", std::to_string(c.p99));
  EXPECT_LT(c.worst, 0.02);
}

}  // namespace
}  // namespace tl::test
