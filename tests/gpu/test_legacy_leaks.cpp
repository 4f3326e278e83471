// The legacy path's voxel GI against the two failures voxel cone tracing is known for:
// light leaking through a wall into a closed room, and voxel-sized steps on flat walls.
// The scene: a sunlit room open to the sky beside a closed room, the wall between them
// thicker than one finest voxel, the sun shining on that wall's lit side. The rooms
// (shared/legacy.h: the finest level's air flooded from where light enters it) keep the
// closed room dark; they must not darken a room lit only through a doorway or by a lamp.
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
// z in [-2, 2], y in [0, 3]. Only the closed room has a roof. With `doorway`, the shared wall
// has a door 1 m wide and 2 m high at its middle.
std::unique_ptr<scene::Scene> makeTwoRooms(bool doorway = false) {
  scene::Material white;
  white.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  white.metallic = 0.0f;
  white.roughness = 1.0f;
  const float T = kWall, x0 = -4.0f - T, x1 = 4.0f + 2.0f * T;
  std::vector<SolidBox> boxes = {
      {{x0, -T, -2.0f - T}, {x1, 0.0f, 2.0f + T}},          // floor
      {{x0, 0.0f, -2.0f - T}, {x1, 3.0f, -2.0f}},           // back wall (-z)
      {{x0, 0.0f, 2.0f}, {x1, 3.0f, 2.0f + T}},             // front wall (+z)
      {{x0, 0.0f, -2.0f}, {-4.0f, 3.0f, 2.0f}},             // lit room's far wall
      {{4.0f + T, 0.0f, -2.0f}, {x1, 3.0f, 2.0f}},          // closed room's far wall
      {{0.0f, 3.0f, -2.0f - T}, {x1, 3.0f + T, 2.0f + T}},  // closed room's roof
  };
  if (doorway) {  // the shared wall around a door
    boxes.push_back({{0.0f, 0.0f, -2.0f}, {T, 3.0f, -0.5f}});
    boxes.push_back({{0.0f, 0.0f, 0.5f}, {T, 3.0f, 2.0f}});
    boxes.push_back({{0.0f, 2.0f, -0.5f}, {T, 3.0f, 0.5f}});
  } else {
    boxes.push_back({{0.0f, 0.0f, -2.0f}, {T, 3.0f, 2.0f}});  // the shared wall
  }
  auto s = makeBoxesScene(white, boxes);
  s->name = doorway ? "two_rooms_doorway" : "two_rooms";
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
  // The legacy path at 64x48 after 8 frames from `position` along `forward`, the rooms' flood at
  // `roomSweeps` rounds (0: off; else the reach image is read back too): the mean luminance of
  // `image`.
  double legacyMean(uint32_t roomSweeps, const std::string& image, glm::dvec3 position, glm::dvec3 forward) {
    auto& s = session();
    s.settings().legacyRoomSweeps = roomSweeps;
    s.setPath("legacy");
    s.setSize(64, 48);
    s.requestBuffer(image);
    if (roomSweeps > 0) s.requestBuffer(kVoxelReach);
    look(position, forward);
    s.renderFrames(8);
    return meanLuminance(image);
  }
  // The two rooms: the lit room first, so the voxels hold its light (and, through the screen,
  // its bounces), then the closed room from inside: the closed room's mean over the lit room's.
  double closedRoomRatio(uint32_t roomSweeps) {
    const double lit = legacyMean(roomSweeps, kCompositeHdr, {-3.6, 1.5, 0.0}, {1.0, -0.1, 0.0});
    const double closed = legacyMean(roomSweeps, kCompositeHdr, {3.6 + kWall, 1.5, 0.0}, {-1.0, -0.1, 0.0});
    std::printf("two rooms, legacyRoomSweeps %u: lit room %.5f, closed room %.5f, ratio %.5f\n", roomSweeps, lit, closed,
                closed / lit);
    EXPECT_GT(lit, 0.1);
    return closed / lit;
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

// The truth in the closed room is black. Measured on lavapipe: 0.0000 % with the rooms (their
// whole image is the sun's shadowed direct light, none); without them (legacyRoomSweeps 0) the
// coarse cones blend in the lit room's light and the sky through the walls: 10.4 %.
TEST_F(LegacyLeakTest, ClosedRoomBesideASunlitOneStaysDark) {
  auto& s = session();
  auto scene = makeTwoRooms();
  const LegacyClipmapFit fit = fitLegacyClipmap(scene->bounds, glm::dvec3(0.0), s.settings().legacyVoxelResolution,
                                                s.settings().legacyLevel0Extent, s.settings().legacyMaxLevels);
  ASSERT_GE(kWall, fit.clipmap.levelMin[0].w) << "the walls must be at least one finest voxel thick";
  s.installScene(std::move(scene));
  lightTwoRooms(s);
  const double withRooms = closedRoomRatio(s.settings().legacyRoomSweeps);
  const double without = closedRoomRatio(0);
  RecordProperty("closed_over_lit", std::to_string(withRooms));
  RecordProperty("closed_over_lit_without_rooms", std::to_string(without));
  EXPECT_LT(withRooms, 0.01);
  EXPECT_GT(without, 0.05) << "without the rooms the cones leak: the scene must show it for the test to mean anything";
}

// The flood runs a fixed number of rounds; only a last round that reaches nothing proves it
// settled. One round here is the whole flood but cannot show it: the cones must ignore it (the
// leak is back); two rounds show it (the second reaches nothing) and the closed room is dark.
TEST_F(LegacyLeakTest, AFloodNotShownToHaveSettledIsIgnored) {
  auto& s = session();
  s.installScene(makeTwoRooms());
  lightTwoRooms(s);
  const double oneRound = closedRoomRatio(1);
  const double twoRounds = closedRoomRatio(2);
  RecordProperty("closed_over_lit_one_round", std::to_string(oneRound));
  RecordProperty("closed_over_lit_two_rounds", std::to_string(twoRounds));
  EXPECT_GT(oneRound, 0.05);
  EXPECT_LT(twoRounds, 0.01);
}

// The same on the project's content/twin_rooms.gltf (walls 1.8 finest voxels thick, the lit
// room lit through a doorway, so far dimmer than the room above): camera 0 in the lit room,
// camera 1 in the closed one. Measured: 0.0000 % (48.0 % without the rooms).
TEST_F(LegacyLeakTest, TwinRoomsClosedRoomStaysDark) {
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
  EXPECT_LT(closed, 0.01 * lit) << "closed " << closed << " lit " << lit;
}

// The rooms' reach image (shared/legacy.h) at world point `p` of the two rooms' scenes,
// whose finest level spans the whole scene (so its placement does not follow the camera).
struct Reach {
  glm::dvec3 min;
  double voxel = 0.0;
  uint32_t R = 0;
  std::vector<float> texels;
  // Sealed, lit and solid voxels whose centres lie inside `box`.
  std::array<size_t, 3> count(const scene::Bounds& box) const {
    std::array<size_t, 3> n{};
    for (uint32_t z = 0; z < R; ++z)
      for (uint32_t y = 0; y < R; ++y)
        for (uint32_t x = 0; x < R; ++x) {
          const glm::dvec3 c = min + (glm::dvec3(x, y, z) + 0.5) * voxel;
          if (glm::any(glm::lessThan(c, box.min)) || glm::any(glm::greaterThan(c, box.max))) continue;
          ++n[std::min<size_t>(size_t(texels[(size_t(z) * R + y) * R + x]), 2)];
        }
    return n;
  }
};
Reach readReach(session::Session& s) {
  const LegacyClipmapFit fit = fitLegacyClipmap(s.scene().bounds, glm::dvec3(0.0), s.settings().legacyVoxelResolution,
                                                s.settings().legacyLevel0Extent, s.settings().legacyMaxLevels);
  Reach r;
  r.min = glm::dvec3(glm::vec3(fit.clipmap.levelMin[0]));
  r.voxel = fit.clipmap.levelMin[0].w;
  r.R = fit.clipmap.resolution;
  const auto& b = s.buffer(kVoxelReach);
  EXPECT_EQ(b.channels(), 1u);
  r.texels = b.texels();
  EXPECT_EQ(r.texels.size(), size_t(r.R) * r.R * r.R);
  return r;
}

// The second room's air, one voxel in from its walls.
scene::Bounds secondRoomAir(double voxel) {
  scene::Bounds b;
  b.min = glm::dvec3(kWall + voxel, voxel, -2.0 + voxel);
  b.max = glm::dvec3(4.0 + kWall - voxel, 3.0 - voxel, 2.0 - voxel);
  return b;
}

// The second room behind a doorway, lit by the sky alone (no sun): no surface in either room
// is lit directly, so the flood starts at the level's outer faces above the open room and
// must pass the door. Every voxel of the second room's air is reached, and its image is the
// same as without the rooms (the gate never fires); with the door walled up, the same room is
// sealed and black.
TEST_F(LegacyLeakTest, ARoomLitThroughADoorwayIsReachedAndKeepsItsLight) {
  auto& s = session();
  auto render = [&](bool doorway, uint32_t roomSweeps) {
    s.installScene(makeTwoRooms(doorway));
    session::Lighting l = s.lighting();
    l.sunIrradiance = glm::vec3(0.0f);
    l.skyRadiance = glm::vec3(1.0f);
    s.setLighting(l);
    return legacyMean(roomSweeps, kCompositeHdr, {3.6 + kWall, 1.5, 1.2}, {-1.0, -0.1, -0.4});
  };
  const uint32_t sweeps = s.settings().legacyRoomSweeps;
  const double withRooms = render(true, sweeps);
  const Reach reach = readReach(s);
  const auto open = reach.count(secondRoomAir(reach.voxel));
  const double without = render(true, 0);
  const double walledUp = render(false, sweeps);
  const auto sealed = readReach(s).count(secondRoomAir(reach.voxel));
  std::printf("second room through a doorway: mean %.5f (without the rooms %.5f), air voxels sealed %zu lit %zu; walled "
              "up: mean %.6f, sealed %zu lit %zu\n",
              withRooms, without, open[0], open[1], walledUp, sealed[0], sealed[1]);
  RecordProperty("doorway_mean", std::to_string(withRooms));
  RecordProperty("doorway_mean_without_rooms", std::to_string(without));
  EXPECT_GT(open[1], 1000u);
  EXPECT_EQ(open[0], 0u) << "air behind the doorway left sealed";
  ASSERT_GT(without, 0.01);
  EXPECT_NEAR(withRooms / without, 1.0, 1e-3);
  EXPECT_EQ(sealed[1], 0u) << "air of the walled-up room reached";
  EXPECT_LT(walledUp, 0.01 * without);
}

// A lamp inside the closed room lights its walls: the flood starts there, the room's air is
// reached, and its image is the same as without the rooms.
TEST_F(LegacyLeakTest, AClosedRoomWithALampInsideKeepsItsLight) {
  auto& s = session();
  auto render = [&](uint32_t roomSweeps) {
    s.installScene(makeTwoRooms());
    lightTwoRooms(s);
    session::Lighting l = s.lighting();
    scene::Light lamp;
    lamp.type = scene::LightType::Point;
    lamp.intensity = 683.0f * 4.0f;  // candela: I = 4 W/sr on the sky's scale
    lamp.position = glm::dvec3(2.0 + kWall, 2.2, 0.3);
    l.lights = {lamp};
    s.setLighting(l);
    return legacyMean(roomSweeps, kCompositeIrradiance, {3.6 + kWall, 1.5, 0.0}, {-1.0, -0.1, 0.0});
  };
  const double withRooms = render(s.settings().legacyRoomSweeps);
  const Reach reach = readReach(s);
  const auto n = reach.count(secondRoomAir(reach.voxel));
  const double without = render(0);
  std::printf("closed room with a lamp: irradiance %.5f (without the rooms %.5f), air voxels sealed %zu lit %zu\n",
              withRooms, without, n[0], n[1]);
  EXPECT_EQ(n[0], 0u);
  ASSERT_GT(without, 0.1);
  EXPECT_NEAR(withRooms / without, 1.0, 1e-3);
}

// The flood's default number of sweep rounds reaches every voxel that 64 rounds reach on the
// project's interiors (rooms joined by doorways, a corridor lit through slits): the default
// is not what decides which rooms are dark.
TEST_F(LegacyLeakTest, TheDefaultSweepsFloodTheInteriorsCompletely) {
  auto& s = session();
  for (const char* file : {"doorway_room.gltf", "slit_corridor.gltf", "twin_rooms.gltf"}) {
    s.loadScene(contentFile(file));
    s.setPath("legacy");
    s.setSize(32, 24);
    s.useSceneCamera(0);
    s.requestBuffer(kVoxelReach);
    s.settings().legacyRoomSweeps = lighting::RenderSettings{}.legacyRoomSweeps;
    s.renderFrames(1);
    const std::vector<float> byDefault = s.buffer(kVoxelReach).texels();
    s.settings().legacyRoomSweeps = 64;
    s.requestBuffer(kVoxelReach);
    s.renderFrames(1);
    ASSERT_EQ(pathFigure(s, "voxelUpdate"), 2.0) << "a new sweep count floods afresh (the voxels are rebuilt)";
    const std::vector<float> converged = s.buffer(kVoxelReach).texels();
    ASSERT_EQ(byDefault.size(), converged.size());
    size_t differ = 0, sealed = 0, lit = 0;
    for (size_t i = 0; i < converged.size(); ++i) {
      differ += byDefault[i] != converged[i];
      sealed += converged[i] == float(shared::kLegacyReachSealed);
      lit += converged[i] == float(shared::kLegacyReachLit);
    }
    std::printf("%s: %zu voxels, sealed %zu, lit %zu, differing from 64 rounds %zu\n", file, converged.size(), sealed, lit,
                differ);
    EXPECT_GT(lit, 0u) << file;
    EXPECT_EQ(differ, 0u) << file;
  }
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

// The step contrast of `image` over the flat middle of the surface whose normal is `normal`,
// seen from `position` along `forward` (with `up`) at 128x96 after 8 frames on the scene
// loaded: pixels at least 12 pixels (~0.4 m, 3 voxels) from the surface's edges, away from
// the corners' darkening (a gradient, not a step).
StepContrast flatStepContrast(session::Session& s, glm::dvec3 position, glm::dvec3 forward, glm::dvec3 up,
                              glm::vec3 normal, const std::string& image) {
  s.setPath("legacy");
  const uint32_t w = 128, h = 96;
  s.setSize(w, h);
  s.requestBuffer(image);
  s.requestBuffer("gbuffer.normal");
  session::View v = s.view();
  v.position = position;
  v.forward = glm::normalize(forward);
  v.up = up;
  v.yfovRadians = 1.0f;
  s.setView(v);
  s.renderFrames(8);
  auto n = s.buffer("gbuffer.normal").texels();
  constexpr int kMargin = 12;
  std::vector<bool> facing(size_t(w) * h), flat(size_t(w) * h);
  for (size_t i = 0; i < facing.size(); ++i)
    facing[i] = glm::dot(shared::tlOctDecode(glm::vec2(n[2 * i], n[2 * i + 1])), normal) > 0.99f;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      bool all = true;
      for (int dy = -kMargin; dy <= kMargin && all; ++dy)
        for (int dx = -kMargin; dx <= kMargin && all; ++dx) {
          const int px = int(x) + dx, py = int(y) + dy;
          all = px >= 0 && py >= 0 && px < int(w) && py < int(h) && facing[size_t(py) * w + px];
        }
      flat[size_t(y) * w + x] = all;
    }
  const auto& b = s.buffer(image);
  StepContrast c = stepContrast(b.texels(), b.channels(), flat, w, h);
  std::printf("%s step contrast: worst %.4f, 99th percentile %.4f over %zu pairs\n", image.c_str(), c.worst, c.p99, c.pairs);
  EXPECT_GT(c.pairs, size_t(w * h / 3)) << "the camera should see the surface";
  return c;
}

// A wall of the two rooms (normal along x).
StepContrast wallStepContrast(session::Session& s, glm::dvec3 position, glm::dvec3 forward, float wallNormal,
                              const std::string& image) {
  s.installScene(makeTwoRooms());
  lightTwoRooms(s);
  return flatStepContrast(s, position, forward, {0.0, 1.0, 0.0}, {wallNormal, 0.0f, 0.0f}, image);
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


// The ceiling of content/doorway_room.gltf (y = 3, facing down), seen from the middle of the
// room 2 m below it (a finest voxel, 0.135 m, is ~6 pixels): no sun reaches it, so all its
// light is the GI of the sunlit floor patch and the walls, where voxel-sized steps would show.
TEST_F(LegacyLeakTest, NoVoxelSizedStepsOnAGiLitCeiling) {
  auto& s = session();
  s.loadScene(contentFile("doorway_room.gltf"));
  const StepContrast c = flatStepContrast(s, {0.0, 1.0, -4.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, -1.0}, {0.0f, -1.0f, 0.0f},
                                          kCompositeHdr);
  RecordProperty("step_contrast_worst", std::to_string(c.worst));
  RecordProperty("step_contrast_p99", std::to_string(c.p99));
  EXPECT_LT(c.worst, 0.02);
}

}  // namespace
}  // namespace tl::test
