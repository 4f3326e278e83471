// The legacy path on lavapipe at small sizes, on scenes with known answers: the open plane
// (AO = 1, irradiance = pi L), AO in a corner of the Cornell box, a box voxelized exactly,
// colour bleeding, persistent voxels, partial voxel updates of an animation, and light
// leaking into the atrium's interior room.
#include "lighting_checks.h"
#include "../common/test_scenes.h"

#include "lighting/legacy/legacy_path.h"
#include "lighting/rt/rt_path.h"
#include "shared/packing.h"
#include "shared/sh.h"

#include <cstring>

namespace tl::test {
namespace {

using namespace lighting;

class LegacyTest : public GpuTest {
 protected:
  void render(const char* path, uint32_t w, uint32_t h, uint32_t frames, const std::vector<std::string>& names) {
    auto& s = session();
    s.setPath(path);
    s.setSize(w, h);
    for (auto& n : names) s.requestBuffer(n);
    s.renderFrames(frames);
  }
  double figure(const std::string& name) { return pathFigure(session(), name); }
};

constexpr double kVoxelsKept = 0.0, kVoxelsPatched = 1.0, kVoxelsRebuilt = 2.0;  // figure voxelUpdate

// Largest difference between two read-backs of the same image, and how many values differ
// by more than `tolerance`.
std::pair<double, size_t> difference(const std::vector<float>& a, const std::vector<float>& b, double tolerance) {
  double worst = 0.0;
  size_t over = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const double d = std::abs(double(a[i]) - double(b[i]));
    worst = std::max(worst, d);
    over += d > tolerance;
  }
  return {worst, over};
}

TEST_F(LegacyTest, PlaneUnderUniformSkyHasNoOcclusionAndIrradiancePiL) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  render("legacy", 64, 40, 1, {kLegacyAo, kLegacyShY, kLegacyCoCg, "gbuffer.depth"});
  PlaneErrors e = planeErrors(s, kLegacyAo, kLegacyShY, kLegacyCoCg);
  ASSERT_GT(e.surface, e.pixels / 4);
  RecordProperty("worst_ao_error", std::to_string(e.worstAo));
  RecordProperty("worst_irradiance_error", std::to_string(e.worstIrradiance));
  // Measured: AO within 5e-4 of 1, irradiance within 0.015% of pi L.
  EXPECT_LE(e.worstAo, 0.005) << "at pixel " << e.worstAoPixel % 64 << ", " << e.worstAoPixel / 64;
  EXPECT_LE(e.worstIrradiance, 0.01) << "cone-traced sky irradiance relative to pi L";
}

// The Cornell box's back wall (by instance id): AO in its top-left corner (against the
// ceiling and the red wall) against its centre.
TEST_F(LegacyTest, AoDarkensACornerOfTheCornellBox) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  const uint32_t backWall = instanceIdOf(s.scene(), "back_wall");
  const uint32_t w = 96, h = 96;
  render("legacy", w, h, 1, {kLegacyAo, "gbuffer.instanceId"});
  auto ao = s.buffer(kLegacyAo).texels();
  const auto& ids = s.buffer("gbuffer.instanceId");
  std::vector<uint32_t> id(w * h);
  std::memcpy(id.data(), ids.bytes.data(), id.size() * 4);
  uint32_t x0 = w, x1 = 0, y0 = h, y1 = 0;
  for (uint32_t i = 0; i < w * h; ++i)
    if (id[i] == backWall) x0 = std::min(x0, i % w), x1 = std::max(x1, i % w), y0 = std::min(y0, i / w), y1 = std::max(y1, i / w);
  ASSERT_GT(x1, x0 + 20);
  auto mean = [&](uint32_t ax, uint32_t bx, uint32_t ay, uint32_t by) {
    double sum = 0.0;
    int n = 0;
    for (uint32_t y = ay; y <= by; ++y)
      for (uint32_t x = ax; x <= bx; ++x)
        if (id[y * w + x] == backWall) sum += ao[y * w + x], ++n;
    return n ? sum / n : -1.0;
  };
  const uint32_t cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  double centre = mean(cx - 2, cx + 2, cy - 2, cy + 2);
  double corner = mean(x0, x0 + 1, y0, y0 + 1);
  RecordProperty("ao_centre", std::to_string(centre));
  RecordProperty("ao_corner", std::to_string(corner));
  EXPECT_GT(centre, 0.0);
  EXPECT_GT(corner, 0.0);
  EXPECT_LT(corner, centre - 0.1) << "corner " << corner << ", centre " << centre;
}

// A cube whose faces sit a quarter voxel inside voxels 15 and 47 (so no edge falls on a
// pixel centre of the voxelizing raster): exactly its 33^3 - 31^3 shell is occupied. (The
// voxel faces sit half a voxel off the scene's centre, so the centred cube spans an odd count.)
TEST_F(LegacyTest, VoxelizationCoversAKnownBoxExactly) {
  scene::Material material;
  material.metallic = 0.0f;
  auto scene = makeCubeScene(material, 2.0f * 16.25f / 32.0f);
  auto& s = session();
  s.installScene(std::move(scene));
  s.settings().legacyLevel0Extent = 2.0f;  // 64 voxels of 1/32 m from -1 + 1/64 m: faces at voxel coordinates 15.25, 47.75
  s.settings().legacyVoxelResolution = 64;
  render("legacy", 32, 32, 1, {kVoxelRadiance});
  const auto& rb = s.buffer(kVoxelRadiance);
  ASSERT_EQ(rb.extent.width, 6u * 64u);
  ASSERT_EQ(rb.extent.depth, 64u) << "one level for a scene smaller than the finest level";
  auto t = rb.texels();
  size_t occupied = 0, outside = 0;
  for (uint32_t z = 0; z < 64; ++z)
    for (uint32_t y = 0; y < 64; ++y)
      for (uint32_t x = 0; x < 64; ++x) {
        bool any = false;
        for (uint32_t f = 0; f < 6; ++f) any |= t[((size_t(z) * 64 + y) * 384 + x + f * 64) * 4 + 3] > 0.0f;
        occupied += any;
        bool shell = x >= 15 && x <= 47 && y >= 15 && y <= 47 && z >= 15 && z <= 47 &&
                     (x == 15 || x == 47 || y == 15 || y == 47 || z == 15 || z == 47);
        outside += any && !shell;
      }
  EXPECT_EQ(occupied, size_t(33 * 33 * 33 - 31 * 31 * 31));
  EXPECT_EQ(outside, 0u);
}

TEST_F(LegacyTest, CornellFloorIsRedderNextToTheRedWall) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  Bleeding b = cornellBleeding(s, "legacy", kLegacyShY, kLegacyCoCg, 8);  // light bounces through the screen over a few frames
  RecordProperty("red_to_green_left", std::to_string(b.left));
  RecordProperty("red_to_green_right", std::to_string(b.right));
  EXPECT_GT(b.left, 1.01 * b.right) << "left (red wall) R/G " << b.left << ", right (green wall) " << b.right;
}

TEST_F(LegacyTest, RayTracedBleedingIsStrongerThanLegacy) {
  auto& s = session();
  if (!s.device().rayTracing().pipeline) GTEST_SKIP() << s.device().rayTracing().unavailableReason;
  s.loadScene(contentFile("cornell.gltf"));
  Bleeding legacy = cornellBleeding(s, "legacy", kLegacyShY, kLegacyCoCg, 8);
  Bleeding rt = cornellBleeding(s, "rt", kShY, kCoCgAo, 24);
  const double legacyContrast = legacy.left / legacy.right, rtContrast = rt.left / rt.right;
  RecordProperty("legacy_contrast", std::to_string(legacyContrast));
  RecordProperty("rt_contrast", std::to_string(rtContrast));
  EXPECT_GT(rtContrast, legacyContrast) << "R/G next to the red wall over R/G next to the green wall";
}

TEST_F(LegacyTest, VoxelsPersistWhileNothingTheyHoldChanges) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  render("legacy", 80, 45, 1, {});
  EXPECT_NE(s.graphDump().find("legacy.voxelize"), std::string::npos) << "the first frame builds the voxels";
  // A few more rebuilds let light bounce through the screen, then they are kept.
  render("legacy", 80, 45, s.settings().legacySettleFrames + 1, {kLegacyShY});
  auto settled = s.buffer(kLegacyShY).texels();
  render("legacy", 80, 45, 1, {"composite.hdr", kLegacyShY, kLegacyAo});
  EXPECT_EQ(s.graphDump().find("legacy.voxelize"), std::string::npos) << "a still camera keeps them";
  auto kept = s.buffer(kLegacyShY).texels();
  EXPECT_EQ(countNonFinite(kept), 0u);
  EXPECT_EQ(countNonFinite(s.buffer("composite.hdr").texels()), 0u);
  EXPECT_EQ(countNonFinite(s.buffer(kLegacyAo).texels()), 0u);
  ASSERT_EQ(settled.size(), kept.size());
  double worst = 0.0;
  for (size_t i = 0; i < kept.size(); ++i) worst = std::max(worst, double(std::abs(settled[i] - kept[i])));
  EXPECT_LE(worst, 1e-3) << "the kept voxels give the GI the last rebuilt ones gave";
  // Moving the sun changes what the voxels hold: they are rebuilt.
  session::Lighting light = s.lighting();
  light.sunDirection = glm::normalize(glm::dvec3(0.5, -0.6, -0.3));
  s.setLighting(light);
  render("legacy", 80, 45, 1, {});
  EXPECT_NE(s.graphDump().find("legacy.voxelize"), std::string::npos);
}

// The banners deform between two frames: the second patches the voxels the banners and
// their shadows reach, and must hold what a rebuild of the same pose holds (mip 0 and the mips;
// of the rooms, every seed and reached voxel a rebuild has). Without screen feedback the voxels depend on nothing but the pose.
TEST_F(LegacyTest, PartialVoxelUpdateMatchesARebuildOfTheSamePose) {
  auto& s = session();
  s.loadScene(contentFile("banners.gltf"));
  ASSERT_TRUE(s.animated());
  s.settings().legacyScreenRadiance = false;
  s.settings().legacyVoxelResolution = 32;
  s.setAnimationStep(0.0);
  s.setAnimationTime(0.3);
  const std::vector<std::string> voxels = {kVoxelRadiance, kVoxelRadianceMips, kVoxelSeeds, kVoxelReach};
  render("legacy", 48, 27, 1, voxels);
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsRebuilt);
  const auto before = s.buffer(kVoxelRadiance).texels();
  s.setAnimationTime(0.8);
  render("legacy", 48, 27, 1, voxels);
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsPatched);
  EXPECT_LT(figure("voxelizedInstances"), double(s.scene().instances.size()));
  const auto patched = s.buffer(kVoxelRadiance).texels(), patchedMips = s.buffer(kVoxelRadianceMips).texels();
  const auto patchedSeeds = s.buffer(kVoxelSeeds).texels(), patchedReach = s.buffer(kVoxelReach).texels();
  s.resetHistory();  // the voxels are lost: the same pose is rebuilt from nothing
  render("legacy", 48, 27, 1, voxels);
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsRebuilt);
  const auto rebuilt = s.buffer(kVoxelRadiance).texels(), rebuiltMips = s.buffer(kVoxelRadianceMips).texels();
  // A patch adds the seeds of what it redraws and keeps the others (legacy_path.cpp): it holds
  // every seed a rebuild finds, and its flood reaches every voxel the rebuild's reaches.
  const auto rebuiltSeeds = s.buffer(kVoxelSeeds).texels(), rebuiltReach = s.buffer(kVoxelReach).texels();
  ASSERT_EQ(patchedSeeds.size(), rebuiltSeeds.size());
  ASSERT_EQ(patchedReach.size(), rebuiltReach.size());
  size_t seedsLost = 0, reachLost = 0, solidDiffers = 0;
  for (size_t i = 0; i < rebuiltSeeds.size(); ++i) {
    seedsLost += rebuiltSeeds[i] != 0.0f && patchedSeeds[i] == 0.0f;
    reachLost += rebuiltReach[i] == float(shared::kLegacyReachLit) && patchedReach[i] != float(shared::kLegacyReachLit);
    solidDiffers += (rebuiltReach[i] == float(shared::kLegacyReachSolid)) != (patchedReach[i] == float(shared::kLegacyReachSolid));
  }
  EXPECT_EQ(seedsLost, 0u);
  EXPECT_EQ(reachLost, 0u);
  EXPECT_EQ(solidDiffers, 0u);
  ASSERT_EQ(patched.size(), rebuilt.size());
  ASSERT_EQ(patchedMips.size(), rebuiltMips.size());
  EXPECT_EQ(countNonFinite(patched), 0u);
  const double tolerance = 0.02;  // radiance and opacity are fp16 of values up to ~5
  auto [moved, movedCount] = difference(before, rebuilt, tolerance);
  auto [worst, over] = difference(patched, rebuilt, tolerance);
  auto [worstMip, overMip] = difference(patchedMips, rebuiltMips, tolerance);
  RecordProperty("pose_change_texels", std::to_string(movedCount));
  RecordProperty("worst_difference", std::to_string(worst));
  RecordProperty("worst_mip_difference", std::to_string(worstMip));
  ASSERT_GT(movedCount, 100u) << "the banners' poses must differ for the comparison to mean anything";
  EXPECT_EQ(over, 0u) << "voxels differing from the rebuild by more than " << tolerance << " (worst " << worst << ")";
  EXPECT_EQ(overMip, 0u) << "mip texels differing from the rebuild by more than " << tolerance << " (worst " << worstMip << ")";
}

// While the banners animate, every frame after the first patches the voxels (fewer instances
// than the scene has); once they stop, the bounces through the screen settle with a few
// rebuilds, then the voxels are kept. Turned off, every animated frame rebuilds.
TEST_F(LegacyTest, AnimationPatchesTheVoxelsThenSettles) {
  auto& s = session();
  s.loadScene(contentFile("banners.gltf"));
  s.settings().legacyVoxelResolution = 32;
  s.setAnimationStep(1.0 / 30.0);
  render("legacy", 48, 27, 2, {kLegacyShY, kLegacyAo});
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsPatched);
  EXPECT_EQ(countNonFinite(s.buffer(kLegacyShY).texels()), 0u);
  EXPECT_EQ(countNonFinite(s.buffer(kLegacyAo).texels()), 0u);
  const double instances = double(s.scene().instances.size());
  RecordProperty("voxelized_instances", std::to_string(figure("voxelizedInstances")));
  RecordProperty("region_voxels", std::to_string(figure("voxelRegionVoxels")));
  EXPECT_GT(figure("voxelizedInstances"), 0.0);
  EXPECT_LT(figure("voxelizedInstances"), instances);
  // banners at R = 32 has three levels (8, 16, 32 m): the banners and their shadows are a
  // small part of them (14% when this was written).
  EXPECT_LT(figure("voxelRegionVoxels"), 0.25 * 3 * 32 * 32 * 32);
  s.setAnimationStep(0.0);
  render("legacy", 48, 27, 1, {});  // the last animated pose is applied
  render("legacy", 48, 27, 1, {});
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsRebuilt) << "bounces settle once the geometry stops";
  render("legacy", 48, 27, s.settings().legacySettleFrames + 1, {});
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsKept);
  s.settings().legacyPartialVoxels = false;
  s.setAnimationStep(1.0 / 30.0);
  render("legacy", 48, 27, 2, {});
  EXPECT_EQ(figure("voxelUpdate"), kVoxelsRebuilt);
  EXPECT_EQ(figure("voxelizedInstances"), instances);
}

// Per-stage error: each path's AO against the reference's AO at the same radius (one
// cosine ray per sample from the primary hit, 256 samples), on the Cornell box.
TEST_F(LegacyTest, AoOfEachPathAgainstTheReferenceAo) {
  auto& s = session();
  if (!s.device().rayTracing().pipeline) GTEST_SKIP() << s.device().rayTracing().unavailableReason;
  s.loadScene(contentFile("cornell.gltf"));
  const uint32_t w = 64, h = 64;
  s.settings().referenceSamplesPerFrame = 64;
  render("reference", w, h, 4, {"reference.ao"});
  auto reference = s.buffer("reference.ao").texels();
  render("legacy", w, h, 8, {kLegacyAo, "gbuffer.depth"});
  auto legacy = s.buffer(kLegacyAo).texels(), depth = s.buffer("gbuffer.depth").texels();
  s.resetHistory();
  render("rt", w, h, 32, {kAo});
  auto rt = s.buffer(kAo).texels();
  double legacyError = 0.0, rtError = 0.0, referenceMean = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    ++n;
    legacyError += std::abs(legacy[i] - reference[i]);
    rtError += std::abs(rt[i] - reference[i]);
    referenceMean += reference[i];
  }
  ASSERT_GT(n, 0u);
  legacyError /= double(n), rtError /= double(n), referenceMean /= double(n);
  RecordProperty("reference_ao_mean", std::to_string(referenceMean));
  RecordProperty("legacy_ao_mean_abs_error", std::to_string(legacyError));
  RecordProperty("rt_ao_mean_abs_error", std::to_string(rtError));
  EXPECT_LT(referenceMean, 0.99) << "the box has corners: some occlusion";
  EXPECT_LT(rtError, 0.05) << "RTAO estimates exactly the reference's definition";
  EXPECT_LT(rtError, legacyError);
}

// Inside the atrium's room, looking up at the underside of its sunlit ceiling (one voxel
// thick at the default resolution): the legacy path's radiance there against the reference
// path tracer's. Light leaking through the ceiling would make it several times brighter; a
// ceiling without its bounce light would be black.
TEST_F(LegacyTest, LightLeakingIntoTheAtriumRoomIsSmall) {
  auto& s = session();
  if (!s.device().rayTracing().pipeline) GTEST_SKIP() << s.device().rayTracing().unavailableReason;
  s.loadScene(contentFile("atrium.gltf"));
  session::View v = s.view();
  v.position = {5.0, 1.2, -7.0};
  v.forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.35));
  v.up = {0.0, 0.0, -1.0};
  v.yfovRadians = 1.0f;
  s.setView(v);
  // Ceiling pixels from the legacy frame's G-buffer (the reference path draws none).
  render("legacy", 48, 48, 8, {"composite.hdr", "gbuffer.normal"});
  auto n = s.buffer("gbuffer.normal").texels();
  std::vector<bool> ceilingPixel(n.size() / 2);
  for (size_t i = 0; i < ceilingPixel.size(); ++i)
    ceilingPixel[i] = shared::tlOctDecode(glm::vec2(n[2 * i], n[2 * i + 1])).y < -0.95f;
  auto mean = [&](const char* image) {
    auto c = s.buffer(image).texels();
    const uint32_t channels = s.buffer(image).channels();
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < ceilingPixel.size(); ++i)
      if (ceilingPixel[i]) sum += shared::tlLuminance(glm::vec3(c[channels * i], c[channels * i + 1], c[channels * i + 2])), ++count;
    return count ? sum / count : -1.0;
  };
  const double legacy = mean("composite.hdr");
  s.settings().referenceSamplesPerFrame = 64;
  render("reference", 48, 48, 4, {"reference.radiance"});
  const double reference = mean("reference.radiance");
  RecordProperty("ceiling_radiance_legacy", std::to_string(legacy));
  RecordProperty("ceiling_radiance_reference", std::to_string(reference));
  ASSERT_GT(reference, 0.0) << "the camera should see the ceiling";
  EXPECT_LT(legacy, 1.5 * reference) << "legacy " << legacy << " vs reference " << reference;
  // And not dark: the ceiling is lit by light bouncing in through the room's openings, which
  // the legacy path under-estimates (measured 0.58 of the reference) but does not lose.
  EXPECT_GT(legacy, 0.3 * reference) << "legacy " << legacy << " vs reference " << reference;
}

}  // namespace
}  // namespace tl::test
