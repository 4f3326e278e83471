// The ray-traced path on lavapipe at small sizes, on scenes with known answers: the open
// plane under a uniform sky (AO = 1, irradiance = pi L), the pre-trace agreeing with real
// rays, colour bleeding in the Cornell box, and finite output on the atrium.
#include "lighting_checks.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/scene_accel.h"
#include "lighting/rt/rt_path.h"
#include "metrics/metrics.h"
#include "shared/packing.h"
#include "shared/rt.h"

#include <cstring>

namespace tl::test {
namespace {

using namespace lighting;

// A read-back integer image's texels (`components` per texel).
std::vector<uint32_t> uints(const graph::Readback& rb, uint32_t components) {
  std::vector<uint32_t> v(rb.bytes.size() / 4);
  std::memcpy(v.data(), rb.bytes.data(), v.size() * 4);
  EXPECT_EQ(v.size(), size_t(rb.extent.width) * rb.extent.height * components);
  return v;
}

class RtTest : public RayTracingTest {
 protected:
  // Renders `frames` RT frames at w x h and reads back `names`.
  void render(uint32_t w, uint32_t h, uint32_t frames, const std::vector<std::string>& names) {
    auto& s = session();
    s.setPath("rt");
    s.setSize(w, h);
    for (auto& n : names) s.requestBuffer(n);
    s.renderFrames(frames);
  }
  // `frames` RT frames on content/plane.gltf (48 x 32) with the current settings: AO = 1 and
  // irradiance = pi L on every surface pixel, within 0.005 and 1% (measured: AO exact,
  // irradiance within 0.24% at full rate, 0.38% at half resolution).
  PlaneErrors expectPlaneConverges(uint32_t frames) {
    session().loadScene(contentFile("plane.gltf"));
    render(48, 32, frames, {kShY, kCoCgAo, kAo, "gbuffer.depth"});
    PlaneErrors e = planeErrors(session(), kAo, kShY, kCoCgAo);
    RecordProperty("worst_ao_error", std::to_string(e.worstAo));
    RecordProperty("worst_irradiance_error", std::to_string(e.worstIrradiance));
    EXPECT_GT(e.surface, e.pixels / 4) << "the plane should fill much of the view";
    EXPECT_LE(e.worstAo, 0.005);
    EXPECT_LE(e.worstIrradiance, 0.01) << "irradiance relative to pi L";
    return e;
  }
};

TEST_F(RtTest, PlaneUnderUniformSkyHasNoOcclusionAndIrradiancePiL) {
  expectPlaneConverges(8);
}

TEST_F(RtTest, HalfRaysPerPixelStillConvergeOnThePlane) {
  session().settings().rtHalfRays = true;
  expectPlaneConverges(6);
}

// Half the rays, the same answer: the mean image after accumulation on the atrium is within a
// few percent of the full-rate one (a misplaced hit record once made it 40x brighter).
TEST_F(RtTest, HalfRaysPerPixelAgreeWithFullRateOnTheAtrium) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  auto meanLuminance = [&](bool half, bool halfResolution = false) {
    s.settings().rtHalfRays = half;
    s.settings().rtHalfResolution = halfResolution;
    s.resetHistory();
    render(80, 45, 16, {"composite.hdr"});
    auto c = s.buffer("composite.hdr").texels();
    EXPECT_EQ(countNonFinite(c), 0u);
    double sum = 0.0;
    for (size_t i = 0; i < c.size(); i += 4) sum += shared::tlLuminance(glm::vec3(c[i], c[i + 1], c[i + 2]));
    return sum / double(c.size() / 4);
  };
  const double full = meanLuminance(false), half = meanLuminance(true), quarter = meanLuminance(false, true);
  RecordProperty("mean_full_rate", std::to_string(full));
  RecordProperty("mean_half_rate", std::to_string(half));
  RecordProperty("mean_half_resolution", std::to_string(quarter));
  EXPECT_NEAR(half / full, 1.0, 0.05);
  EXPECT_NEAR(quarter / full, 1.0, 0.05) << "half resolution (0.25 rays per pixel)";
}

// Half resolution on the plane converges, and every pixel got samples: after 12 frames
// (three of each 2x2 position) all have history.
void expectHalfResolutionAccumulatesEverywhere(session::Session& s) {
  auto c = s.buffer(kCoCgAo).texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  size_t unaccumulated = 0;
  for (size_t i = 0; i < depth.size(); ++i) unaccumulated += depth[i] > 0.0f && c[4 * i + 3] < 11.0f;
  EXPECT_EQ(unaccumulated, 0u);
}

TEST_F(RtTest, HalfResolutionStillConvergesOnThePlane) {
  auto& s = session();
  s.settings().rtHalfResolution = true;
  expectPlaneConverges(12);
  expectHalfResolutionAccumulatesEverywhere(s);
}

// The same under TAA's jitter: the history texel's centre moves by up to a pixel on a
// grazing plane, which a fixed 3% depth tolerance took for another surface (336 of 1,536
// pixels lost their history); the tolerance now follows the depth's step between pixels.
TEST_F(RtTest, HalfResolutionKeepsItsHistoryUnderTaaJitter) {
  auto& s = session();
  s.settings().rtHalfResolution = true;
  s.settings().taa = true;
  expectPlaneConverges(12);
  expectHalfResolutionAccumulatesEverywhere(s);
}

// A camera cut rejects all history: after many still frames, the first frame from a view
// that shares no surface with the last one accumulates nothing old.
TEST_F(RtTest, CameraCutRejectsHistory) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  // The radiance cache off: this is about the temporal history alone (a warming cache
  // shortens the history's window to half its own age, RtRadianceCache::temporalWindow).
  s.settings().rtCacheMinGain = 2.0f;
  session::View v = s.view();
  v.position = {0.0, 1.7, 8.0};
  v.forward = {0.0, 0.0, -1.0};
  v.up = {0.0, 1.0, 0.0};
  s.setView(v);
  render(48, 27, 12, {kCoCgAo});
  auto still = s.buffer(kCoCgAo).texels();
  float maxFrames = 0.0f;
  for (size_t i = 3; i < still.size(); i += 4) maxFrames = std::max(maxFrames, still[i]);
  EXPECT_GE(maxFrames, 11.0f) << "a still camera accumulates";
  v.position = {5.0, 1.5, -7.0};  // inside the room, looking at its north wall
  v.forward = {0.0, -0.1, -1.0};
  s.setView(v);
  render(48, 27, 1, {kCoCgAo});
  auto cut = s.buffer(kCoCgAo).texels();
  size_t old = 0;
  for (size_t i = 3; i < cut.size(); i += 4) old += cut[i] > 1.0f;
  EXPECT_EQ(old, 0u) << "pixels that kept history across the cut";
}

// Per pixel, the luminance of the irradiance an SH image pair (coCg with 4 channels) resolves
// to at the G-buffer normal; the normal must have been read back with them.
std::vector<double> irradianceLuma(session::Session& s, const std::string& shYName, const std::string& coCgName) {
  auto shY = s.buffer(shYName).texels(), coCg = s.buffer(coCgName).texels();
  auto n = s.buffer("gbuffer.normal").texels();
  std::vector<double> out(n.size() / 2);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = shared::tlLuminance(irradianceAt(shY, coCg, 4, i, shared::tlOctDecode(glm::vec2(n[2 * i], n[2 * i + 1]))));
  return out;
}
// relMSE of x against `truth` over the surface pixels (depth > 0), with 0.01 added below.
double surfaceRelMse(const std::vector<double>& x, const std::vector<double>& truth, const std::vector<float>& depth) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    sum += (x[i] - truth[i]) * (x[i] - truth[i]) / (truth[i] * truth[i] + 0.01), ++n;
  }
  return sum / double(std::max<size_t>(n, 1));
}

// Disocclusion rays (RE ENGINE): after a camera cut every pixel has one sample; with 16 rays
// per 8x8 cell filled in, the first frame's accumulated irradiance is closer to the converged
// one by a stated factor. A still camera, once settled, traces no cell at all.
TEST_F(RtTest, DisocclusionRaysBringACutCloserToConverged) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  // The radiance cache off: this is about the temporal history alone (a warming cache
  // shortens the history's window to half its own age, RtRadianceCache::temporalWindow).
  s.settings().rtCacheMinGain = 2.0f;
  const uint32_t w = 64, h = 36;
  session::View before = s.view();
  before.position = {0.0, 1.7, 8.0};  // the yard, then a cut to inside the room
  before.forward = {0.0, 0.0, -1.0};
  before.up = {0.0, 1.0, 0.0};
  session::View after = before;
  after.position = {5.0, 1.5, -7.0};
  after.forward = glm::normalize(glm::dvec3(0.0, -0.1, -1.0));
  auto luma = [&](const std::string& shYName, const std::string& coCgName) { return irradianceLuma(s, shYName, coCgName); };
  s.setView(after);
  s.settings().rtDenoise = false;
  s.settings().rtMaxAccumFrames = 4096;
  render(w, h, 256, {kShY, kCoCgAo, "gbuffer.normal", "gbuffer.depth"});
  const auto converged = luma(kShY, kCoCgAo);
  const auto depth = s.buffer("gbuffer.depth").texels();
  auto relMse = [&](const std::vector<double>& x) { return surfaceRelMse(x, converged, depth); };
  // The cut: a few frames at the first view, then one at the second.
  auto firstFrameAfterCut = [&](uint32_t rays, const std::string& shYName, const std::string& coCgName) {
    s.settings() = RenderSettings{};
    s.settings().rtDenoise = false;
    s.settings().rtDisocclusionRays = rays;
    s.resetHistory();
    s.setView(before);
    render(w, h, 4, {});
    s.setView(after);
    render(w, h, 1, {shYName, coCgName, "gbuffer.normal"});
    return relMse(luma(shYName, coCgName));
  };
  const double without = firstFrameAfterCut(0, kShY, kCoCgAo);
  const double with = firstFrameAfterCut(16, kFilledShY, kFilledCoCgAo);
  RecordProperty("relmse_cut_without", std::to_string(without));
  RecordProperty("relmse_cut_with", std::to_string(with));
  EXPECT_LT(with * 5.0, without) << "one ray " << without << ", with 16 disocclusion rays per cell " << with;

  // Still, settled: no pixel is fresh, so no cell traces.
  render(w, h, 3, {kCellOrigin, kFilledCoCgAo});
  const auto origins = s.buffer(kCellOrigin).texels();
  size_t traced = 0;
  for (size_t i = 3; i < origins.size(); i += 4) traced += origins[i] > 0.0f;
  EXPECT_EQ(traced, 0u) << "cells traced by a still camera";
  for (float v : s.buffer(kFilledCoCgAo).texels()) ASSERT_TRUE(std::isfinite(v));
}

// The spatial denoiser on one frame: its irradiance is closer to the converged one (256
// accumulated frames, denoiser off) than the raw frame's, by a stated factor; and the raw
// frame of two rays per pixel about halves the one ray's error.
TEST_F(RtTest, DenoisedSingleFrameIsCloserToConvergedThanRaw) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  const uint32_t w = 64, h = 64;
  auto luma = [&](const std::string& shYName, const std::string& coCgName) { return irradianceLuma(s, shYName, coCgName); };
  s.settings().rtDenoise = false;
  s.settings().rtMaxAccumFrames = 4096;
  render(w, h, 256, {kShY, kCoCgAo, "gbuffer.normal", "gbuffer.depth"});
  const auto converged = luma(kShY, kCoCgAo);
  const auto depth = s.buffer("gbuffer.depth").texels();
  s.settings() = RenderSettings{};
  s.resetHistory();
  render(w, h, 1, {kShY, kCoCgAo, kDenoisedShY, kDenoisedCoCgAo, "gbuffer.normal"});
  const auto raw = luma(kShY, kCoCgAo), denoised = luma(kDenoisedShY, kDenoisedCoCgAo);
  auto relMse = [&](const std::vector<double>& x) { return surfaceRelMse(x, converged, depth); };
  const double rawError = relMse(raw), denoisedError = relMse(denoised);
  RecordProperty("relmse_raw", std::to_string(rawError));
  RecordProperty("relmse_denoised", std::to_string(denoisedError));
  EXPECT_LT(denoisedError * 2.0, rawError) << "raw " << rawError << ", denoised " << denoisedError;

  // Two rays per pixel: the raw frame is the mean of two independent rays, so its error
  // against the converged irradiance is about half the one ray's (the mean over 4 frames each;
  // emitter sampling off, whose rare near-field spikes would decide a single frame's relMSE).
  auto firstFrameError = [&](bool twoRays) {
    s.settings().rtTwoRays = twoRays;
    s.settings().rtEmitterSampling = false;
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      s.resetHistory();
      render(w, h, 1, {kShY, kCoCgAo, "gbuffer.normal"});
      sum += relMse(luma(kShY, kCoCgAo));  // the first frame: the raw sample (mean of both rays)
    }
    return sum / 4.0;
  };
  const double oneRay = firstFrameError(false), twoRays = firstFrameError(true);
  RecordProperty("relmse_raw_one_ray", std::to_string(oneRay));
  RecordProperty("relmse_raw_two_rays", std::to_string(twoRays));
  EXPECT_LT(twoRays, 0.75 * oneRay) << "measured 0.65x; one ray " << oneRay << ", two " << twoRays;
  EXPECT_GT(twoRays, 0.3 * oneRay) << "two rays, not more";
}

TEST_F(RtTest, PretraceAgreesWithRealRaysWhereBothHit) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  // The same frame index twice: identical rays, once pre-traced, once all real.
  s.setFrameIndex(5);
  render(96, 96, 1, {kPretraceHits, "gbuffer.depth"});
  auto pre = uints(s.buffer(kPretraceHits), 1);
  auto depth = s.buffer("gbuffer.depth").texels();
  s.settings().rtPretrace = false;
  s.setFrameIndex(5);
  render(96, 96, 1, {kHits});
  auto real = uints(s.buffer(kHits), 1);

  size_t surface = 0, preHits = 0, bothHit = 0, agree = 0;
  for (size_t i = 0; i < pre.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    ++surface;
    if (!shared::tlRtIsHit(pre[i])) continue;
    ++preHits;
    if (!shared::tlRtIsHit(real[i])) continue;
    ++bothHit;
    double a = shared::tlRtHitDistance(pre[i]), b = shared::tlRtHitDistance(real[i]);
    agree += std::abs(a - b) <= 0.05 * b + 0.01;
  }
  ASSERT_GT(surface, 0u);
  const double saved = double(preHits) / double(surface);
  const double agreement = bothHit ? double(agree) / double(bothHit) : 0.0;
  RecordProperty("pretrace_share", std::to_string(saved));
  RecordProperty("pretrace_agreement", std::to_string(agreement));
  EXPECT_GT(saved, 0.05) << "the pre-trace should answer some rays inside a box";
  EXPECT_GE(double(bothHit), 0.95 * double(preHits)) << "a pre-trace hit must be a real surface";
  EXPECT_GE(agreement, 0.9) << "distances of pre-traced and real hits";
}

// Pre-traced (the deformed depth buffer) against real rays (the bottom levels) on the
// banners, posed at `seconds`: the share of rays hitting in both whose distances agree.
double bannerAgreement(session::Session& s, uint32_t frameIndex) {
  s.setFrameIndex(frameIndex);
  s.settings().rtPretrace = true;
  s.settings().rtPretracePixels = 128.0f;  // long marches at this small size: more rays to compare
  s.setPath("rt");
  s.setSize(96, 64);
  for (std::string_view n : std::initializer_list<std::string_view>{kPretraceHits, "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(1);
  auto pre = uints(s.buffer(kPretraceHits), 1);
  s.settings().rtPretrace = false;
  s.setFrameIndex(frameIndex);
  s.requestBuffer(kHits);
  s.renderFrames(1);
  auto real = uints(s.buffer(kHits), 1);
  s.settings().rtPretrace = true;
  size_t both = 0, agree = 0;
  for (size_t i = 0; i < pre.size(); ++i) {
    if (!shared::tlRtIsHit(pre[i]) || !shared::tlRtIsHit(real[i])) continue;
    ++both;
    double a = shared::tlRtHitDistance(pre[i]), b = shared::tlRtHitDistance(real[i]);
    agree += std::abs(a - b) <= 0.05 * b + 0.01;
  }
  return both ? double(agree) / double(both) : 0.0;
}

// Deforming meshes: the bottom levels are built in the pose of the first frame (t = 0); at
// t = 0.55 s, with every stale level refitted, real rays see the pose the raster drew; with
// refits off they still see the first pose, and disagree with the pre-trace.
TEST_F(RtTest, RefittedBottomLevelsFollowTheDeformedMeshes) {
  auto& s = session();
  auto figure = [&](const char* name) { return pathFigure(s, name); };
  auto agreementAfterAMove = [&](uint32_t top, uint32_t random) {
    s.loadScene(contentFile("banners.gltf"));
    s.settings().rtRefitTop = top;
    s.settings().rtRefitRandom = random;
    s.setAnimationTime(0.0);
    bannerAgreement(s, 2);
    s.setAnimationTime(0.55);
    return bannerAgreement(s, 3);
  };
  const double refitted = agreementAfterAMove(64, 0);
  EXPECT_EQ(figure("deformingMeshes"), 48.0);
  EXPECT_EQ(figure("blasStale"), 0.0) << "the second of the pair: nothing moved since the first";
  const double stale = agreementAfterAMove(0, 0);
  EXPECT_EQ(figure("blasStale"), 48.0);
  EXPECT_EQ(figure("blasRefits"), 0.0);
  RecordProperty("agreement_refitted", std::to_string(refitted));
  RecordProperty("agreement_never_refitted", std::to_string(stale));
  std::printf("pre-trace / real-ray agreement on the banners: refitted %.3f, never refitted %.3f\n", refitted, stale);
  EXPECT_GE(refitted, 0.75);
  EXPECT_LT(stale, refitted - 0.1);
}

// Distance culling follows the GI blend distance: beyond it the path's GI is not used (the
// far field's is), so the top level keeps what rays from nearer surfaces can reach (the blend
// distance plus the ray length) and the image is the one without culling.
TEST_F(RtTest, TopLevelDistanceCullingFollowsTheBlendDistance) {
  auto& s = session();
  s.loadScene(contentFile("grove.gltf"));
  s.useSceneCamera(1);  // the overview: the grid from 40 m up, 60 to 280 m away
  // Rays a tenth of the grove long (the automatic length, the whole scene, reaches every
  // instance from anywhere: nothing could be culled).
  s.settings().rtRayLength = 0.1f * float(s.sceneSize().diagonal);
  auto figure = [&](const char* name) { return pathFigure(s, name); };
  auto frame = [&](float blend, float margin, float angle) {
    s.settings().rtBlendDistance = blend;
    s.settings().rtCullMargin = margin;
    s.settings().rtCullAngle = angle;
    s.resetHistory();
    s.setFrameIndex(3);
    render(64, 36, 1, {"composite.hdr"});
    return std::make_pair(figure("tlasInstances"), s.buffer("composite.hdr").texels());
  };
  const auto [withBlend, culled] = frame(100.0f, 0.0f, 0.0f);
  const auto [withoutBlend, unused] = frame(0.0f, 0.0f, 0.0f);  // the default: beyond the whole grove
  const auto [all, full] = frame(100.0f, 1e6f, 0.0f);           // a margin that keeps everything
  RecordProperty("tlas_instances_blend_100m", std::to_string(withBlend));
  RecordProperty("tlas_instances_default_blend", std::to_string(withoutBlend));
  EXPECT_GE(all, 10000.0);
  EXPECT_LT(withBlend, 0.8 * withoutBlend) << "the blend distance culls nothing";
  ASSERT_EQ(culled.size(), full.size());
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < full.size(); i += 4)
    for (int c = 0; c < 3; ++c) diff += std::abs(culled[i + c] - full[i + c]), sum += std::abs(full[i + c]);
  RecordProperty("relative_image_difference", std::to_string(diff / sum));
  EXPECT_LE(diff / sum, 1e-3) << "distance culling must not change what the frame shows";
}

// Metro's distance blend: beyond the blend distance the legacy path's GI, not the sky. Its
// passes join the frame only when part of the scene lies that far.
TEST_F(RtTest, BeyondTheBlendDistanceTheLegacyGiTakesOver) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  s.setSize(64, 36);
  auto meanFarIrradiance = [&](const std::string& path, bool farLegacy, float blend) {
    s.setPath(path);
    s.settings().rtFarLegacy = farLegacy;
    s.settings().rtBlendDistance = blend;
    s.resetHistory();
    for (std::string_view n : std::initializer_list<std::string_view>{lighting::kCompositeIrradiance, "gbuffer.depth"}) s.requestBuffer(n);
    s.renderFrames(6);
    auto e = s.buffer(lighting::kCompositeIrradiance).texels();
    auto depth = s.buffer("gbuffer.depth").texels();
    double sum = 0.0;
    size_t n = 0;
    // Far pixels: view depth beyond the blend distance (reversed Z: depth = near / w).
    const float near = s.view().znear;
    for (size_t i = 0; i < depth.size(); ++i) {
      if (depth[i] <= 0.0f || near / depth[i] < 1.2f * blend) continue;
      sum += shared::tlLuminance(glm::vec3(e[4 * i], e[4 * i + 1], e[4 * i + 2]));
      ++n;
    }
    EXPECT_GT(n, 100u) << "far pixels";
    return n ? sum / double(n) : 0.0;
  };
  const double legacy = meanFarIrradiance("legacy", true, 8.0f);
  const double rtFar = meanFarIrradiance("rt", true, 8.0f);
  EXPECT_NE(s.graphDump().find("legacy.cones"), std::string::npos);
  const double rtSky = meanFarIrradiance("rt", false, 8.0f);
  EXPECT_EQ(s.graphDump().find("legacy.cones"), std::string::npos);
  std::printf("far-field irradiance: legacy %.3f, rt + legacy far field %.3f, rt + sky %.3f\n", legacy, rtFar, rtSky);
  EXPECT_NEAR(rtFar, legacy, 0.1 * legacy) << "the far field is the legacy GI";
  EXPECT_GT(std::abs(rtSky - legacy), 0.2 * legacy) << "the sky alone is a different answer";
  // The default blend distance lies beyond the whole scene: no legacy passes.
  s.settings() = lighting::RenderSettings{};
  s.setSize(64, 36);
  s.renderFrames(1);
  EXPECT_EQ(s.graphDump().find("legacy."), std::string::npos);
}

TEST_F(RtTest, CornellFloorIsRedderNextToTheRedWall) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  Bleeding b = cornellBleeding(s, "rt", kShY, kCoCgAo, 24);
  ASSERT_GT(b.floorWidth, 10u);
  RecordProperty("red_to_green_left", std::to_string(b.left));
  RecordProperty("red_to_green_right", std::to_string(b.right));
  EXPECT_GT(b.left, 1.1 * b.right) << "left (red wall) R/G " << b.left << ", right (green wall) " << b.right;
}

TEST_F(RtTest, AtriumStaysFiniteAndItsIntermediatesAreNamed) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  render(80, 45, 3, {kShY, kCoCgAo, kAo, "composite.hdr"});
  for (std::string_view n : std::initializer_list<std::string_view>{kShY, kCoCgAo, kAo, "composite.hdr"}) EXPECT_EQ(countNonFinite(s.buffer(n).texels()), 0u) << n;
  const std::string dump = s.graphDump();
  for (std::string_view n : std::initializer_list<std::string_view>{kAccelSimplified.tlas, kPretraceHits, kHits, kHitSurface, kRawShY, kRawAo, kShY, kAo, kHistShY})
    EXPECT_NE(dump.find(n), std::string::npos) << n;
}

// 10,000 instances, a camera at the corner looking out, rays a tenth of the grove long: the
// top level keeps only what rays from the visible surfaces can reach (the automatic margin is
// the ray's length), and the image is the one without culling. With the automatic ray length
// (the whole scene) every instance is in reach and nothing may be culled.
TEST_F(RtTest, TopLevelCullingKeepsFewInstancesAndChangesNothing) {
  auto& s = session();
  s.loadScene(contentFile("grove.gltf"));
  s.settings().rtRayLength = 0.1f * float(s.sceneSize().diagonal);
  auto figure = [&](const char* name) { return pathFigure(s, name); };
  s.setFrameIndex(3);
  render(64, 36, 1, {"composite.hdr"});
  const double kept = figure("tlasInstances"), total = figure("sceneInstances");
  auto culled = s.buffer("composite.hdr").texels();
  s.settings().rtCullMargin = 1e6f;  // keep everything
  s.settings().rtCullAngle = 0.0f;
  s.resetHistory();
  s.setFrameIndex(3);
  render(64, 36, 1, {"composite.hdr"});
  const double all = figure("tlasInstances");
  auto full = s.buffer("composite.hdr").texels();
  RecordProperty("tlas_instances_culled", std::to_string(kept));
  RecordProperty("tlas_instances_all", std::to_string(all));
  EXPECT_GE(total, 10000.0);
  EXPECT_EQ(all, total);
  EXPECT_LE(kept, 5000.0);
  EXPECT_GT(kept, 0.0);
  ASSERT_EQ(culled.size(), full.size());
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < full.size(); i += 4)
    for (int c = 0; c < 3; ++c) diff += std::abs(culled[i + c] - full[i + c]), sum += std::abs(full[i + c]);
  RecordProperty("relative_image_difference", std::to_string(diff / sum));
  EXPECT_LE(diff / sum, 1e-3) << "culling must not change what rays hit";
  s.settings() = lighting::RenderSettings{};
  s.resetHistory();
  s.setFrameIndex(3);
  render(64, 36, 1, {"composite.hdr"});
  EXPECT_EQ(figure("tlasInstances"), total) << "rays as long as the scene reach every instance";
}

// Mean luma of the accumulated irradiance (SH L0) over surface pixels after `frames` more
// frames, history kept; every value finite.
double meanSurfaceLuma(session::Session& s, uint32_t frames) {
  s.requestBuffer(kShY);
  s.requestBuffer("gbuffer.depth");
  s.renderFrames(frames);
  auto shY = s.buffer(kShY).texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  EXPECT_EQ(countNonFinite(shY), 0u);
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < depth.size(); ++i)
    if (depth[i] > 0.0f) sum += shY[4 * i], ++n;
  return sum / double(std::max<size_t>(n, 1));
}

// The same from a fresh history, on the RT path at w x h.
double meanAccumulatedLuma(session::Session& s, uint32_t w, uint32_t h, uint32_t frames) {
  s.resetHistory();
  s.setPath("rt");
  s.setSize(w, h);
  return meanSurfaceLuma(s, frames);
}

// A light switched off does not ghost (RE ENGINE's temporal luminance rejection): after the
// atrium's sky and sun go dark without a history reset (default settings: hits that reuse
// last frame's image are lit afresh in that frame), the accumulated irradiance is gone at
// once, where the plain 1/n average would keep most of it for the whole window; switched
// back on over the dark history, it is back within a few frames.
TEST_F(RtTest, LightSwitchedOffDoesNotGhost) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  const session::Lighting daylight = s.lighting();
  session::Lighting dark = daylight;
  dark.skyRadiance = glm::vec3(0.0f);
  dark.sunIrradiance = glm::vec3(0.0f);
  auto afterSwitchOff = [&](bool rejection) {
    s.settings() = RenderSettings{};
    s.settings().rtLumaRejection = rejection;
    s.settings().rtCacheMinGain = 2.0f;  // the cache off: this is about the temporal history alone
    s.setLighting(daylight);
    const double lit = meanAccumulatedLuma(s, 64, 36, 24);
    s.setLighting(dark);
    const double left = meanSurfaceLuma(s, 6);  // no reset: the history sees the change
    s.setLighting(daylight);
    return left / lit;
  };
  const double kept = afterSwitchOff(true), keptWithout = afterSwitchOff(false);
  RecordProperty("fraction_left_with_rejection", std::to_string(kept));
  RecordProperty("fraction_left_without", std::to_string(keptWithout));
  std::printf("6 frames after the light went off: %.3f of it left with rejection, %.3f without\n", kept, keptWithout);
  EXPECT_LT(kept, 0.1);
  EXPECT_GT(keptWithout, 0.5) << "without rejection the 1/n average holds on (the test's premise)";
  // And switched on over a dark history: the new light is in within a few frames.
  s.settings() = RenderSettings{};
  s.setLighting(daylight);
  const double lit = meanAccumulatedLuma(s, 64, 36, 24);
  s.setLighting(dark);
  s.renderFrames(24);
  s.setLighting(daylight);
  const double reached = meanSurfaceLuma(s, 6) / lit;
  std::printf("6 frames after the light came back: %.3f of it there\n", reached);
  RecordProperty("fraction_after_switch_on", std::to_string(reached));
  EXPECT_GT(reached, 0.75) << "the plain 1/n average would have about 6/30 of it";
}

// Fireflies of 1e4 (content/sparks.gltf: rays from the ground rarely find tiny emitters 1e4
// times brighter than the sky): every stage stays finite with or without the firefly clamp.
// With it the mean converges (frames 33-64 agree with 1-32), the brightest accumulated pixel
// is bounded, and most of the light is kept; without it a handful of rays a frame still
// swing the mean by tens of percent.
TEST_F(RtTest, FirefliesOf1e4StayFiniteAndConverge) {
  auto& s = session();
  s.loadScene(contentFile("sparks.gltf"));
  struct Run {
    double early = 0.0, late = 0.0, brightest = 0.0;
  };
  auto run = [&](float clamp, bool emitterSampling) {
    s.settings() = RenderSettings{};
    s.settings().rtFireflyClamp = clamp;
    s.settings().rtEmitterSampling = emitterSampling;
    s.settings().rtMaxAccumFrames = 64;
    Run r;
    r.early = meanAccumulatedLuma(s, 48, 32, 32);
    for (std::string_view n : std::initializer_list<std::string_view>{kShY, kDenoisedShY, "composite.hdr", "gbuffer.depth"}) s.requestBuffer(n);
    s.renderFrames(32);
    auto shY = s.buffer(kShY).texels();
    EXPECT_EQ(countNonFinite(shY), 0u);
    EXPECT_EQ(countNonFinite(s.buffer(kDenoisedShY).texels()), 0u);
    EXPECT_EQ(countNonFinite(s.buffer("composite.hdr").texels()), 0u);
    auto depth = s.buffer("gbuffer.depth").texels();
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < depth.size(); ++i)
      if (depth[i] > 0.0f) sum += shY[4 * i], r.brightest = std::max(r.brightest, double(shY[4 * i])), ++n;
    r.late = sum / double(std::max<size_t>(n, 1));
    return r;
  };
  // The rays alone must find the emitters: the case the clamp is for.
  const Run off = run(0.0f, false), on = run(16.0f, false);
  // Emitter sampling reaches them through a shadow ray from every pixel: no spikes to clamp.
  const Run sampled = run(0.0f, true);
  std::printf("sparks mean luma after 32 / 64 frames: clamp off %.3f / %.3f (brightest %.1f), clamp 16x %.3f / %.3f "
              "(brightest %.1f), emitter sampling %.3f / %.3f (brightest %.1f)\n",
              off.early, off.late, off.brightest, on.early, on.late, on.brightest, sampled.early, sampled.late,
              sampled.brightest);
  RecordProperty("mean_luma_64_emitter_sampling", std::to_string(sampled.late));
  RecordProperty("brightest_emitter_sampling", std::to_string(sampled.brightest));
  EXPECT_NEAR(sampled.late / sampled.early, 1.0, 0.02) << "emitter sampling converges without a clamp";
  EXPECT_LT(sampled.brightest, 0.2 * off.brightest);
  RecordProperty("mean_luma_64_clamp_off", std::to_string(off.late));
  RecordProperty("mean_luma_64_clamp_on", std::to_string(on.late));
  RecordProperty("brightest_clamp_off", std::to_string(off.brightest));
  RecordProperty("brightest_clamp_on", std::to_string(on.brightest));
  EXPECT_NEAR(on.late / on.early, 1.0, 0.05) << "converging: frames 33-64 agree with 1-32";
  EXPECT_LT(on.brightest, 0.1 * off.brightest) << "the clamp bounds the spikes";
  EXPECT_GT(on.late, 0.5 * off.late) << "and keeps the rest of the light";
  // On smooth light the clamp changes nothing: the open plane under the sky.
  // (The same rays both times: the mean SH luma of 8 frames depends on their directions.)
  s.loadScene(contentFile("plane.gltf"));
  s.settings() = RenderSettings{};
  s.setFrameIndex(0);
  const double plain = meanAccumulatedLuma(s, 48, 32, 8);
  s.settings().rtFireflyClamp = 16.0f;
  s.setFrameIndex(0);
  EXPECT_NEAR(meanAccumulatedLuma(s, 48, 32, 8) / plain, 1.0, 1e-3);
}

// The yardstick: with a still camera, the RT path's diffuse irradiance after 64
// frames (denoised) against the reference's irradiance, over surface pixels away from
// silhouettes (the reference jitters inside a pixel), 512 spp (cornell) and 256 (atrium), in
// two scopes: the reference's full bounce policy against the paths' defaults (their
// screen feedback approximates the bounces beyond the first), and the reference's one bounce
// against both paths without their feedback (what their rays compute by design). RT must stay
// within a stated relMSE and below the legacy path's in both.
struct IrradianceErrors {
  double rt = 0.0, legacy = 0.0;
  double rtNoCache = -1.0;  // with alsoWithoutCache: every bounce, the RT path without its radiance cache
};
enum class Scope { Full, OneBounce };
IrradianceErrors irradianceErrors(session::Session& s, const char* scene, uint32_t w, uint32_t h,
                                  uint32_t referenceFrames, Scope scope, bool alsoWithoutCache = false) {
  s.loadScene(contentFile(scene));
  s.settings() = RenderSettings{};  // (holds the size too: set it after)
  s.setSize(w, h);
  s.settings().referenceSamplesPerFrame = 64;
  if (scope == Scope::OneBounce) {
    // Direct light and one bounce: the paths without their screen feedback and the RT path
    // without its radiance cache (each adds the later bounces).
    s.settings().referenceBounces = 2;
    s.settings().rtScreenRadiance = false;
    s.settings().legacyScreenRadiance = false;
  }
  if (scope != Scope::Full) s.settings().rtCacheMinGain = 2.0f;  // above 1: never
  auto irradiance = [&](const char* path, uint32_t frames, const std::string& name) {
    s.setPath(path);
    s.resetHistory();
    s.setFrameIndex(0);  // the same noise whatever ran before
    // The reference's irradiance accumulates only in frames that read it: read every frame;
    // the paths' is their last frame's.
    const bool everyFrame = std::string_view(path) == "reference";
    for (uint32_t f = 0; f < frames; ++f) {
      if (everyFrame || f + 1 == frames) {
        s.requestBuffer(name);
        s.requestBuffer("gbuffer.depth");
      }
      s.renderFrames(1);
    }
    auto t = s.buffer(name).texels();
    const uint32_t c = s.buffer(name).channels();
    std::vector<float> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < size_t(w) * h; ++i)
      for (int k = 0; k < 3; ++k) rgb[3 * i + k] = t[c * i + k];
    EXPECT_EQ(countNonFinite(rgb), 0u) << path;
    return rgb;
  };
  const auto reference = irradiance("reference", referenceFrames, "reference.irradiance");
  const auto legacy = irradiance("legacy", 8, lighting::kCompositeIrradiance);
  const auto rt = irradiance("rt", 64, lighting::kCompositeIrradiance);
  std::vector<float> rtNoCache;
  if (alsoWithoutCache) {  // the same reference and legacy image: only rt again
    s.settings().rtCacheMinGain = 2.0f;
    rtNoCache = irradiance("rt", 64, lighting::kCompositeIrradiance);
  }
  const auto depth = s.buffer("gbuffer.depth").texels();
  auto interior = [&](size_t i) {
    const size_t x = i % w, y = i / w;
    if (x == 0 || y == 0 || x + 1 == w || y + 1 == h) return false;
    for (size_t j : {i, i - 1, i + 1, i - w, i + w})
      if (depth[j] <= 0.0f) return false;
    return true;
  };
  auto relMse = [&](const std::vector<float>& test) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < depth.size(); ++i) {
      if (!interior(i)) continue;
      for (int k = 0; k < 3; ++k) {
        const double r = reference[3 * i + k], d = test[3 * i + k] - r;
        sum += d * d / (r * r + metrics::kRelMseEpsilon), ++n;
      }
    }
    EXPECT_GT(n, depth.size());  // most pixels are interior surface (3 channels each)
    return sum / double(std::max<size_t>(n, 1));
  };
  return {relMse(rt), relMse(legacy), rtNoCache.empty() ? -1.0 : relMse(rtNoCache)};
}

TEST_F(RtTest, After64FramesIrradianceBeatsLegacyAgainstTheReference) {
  auto& s = session();
  const IrradianceErrors cornell = irradianceErrors(s, "cornell.gltf", 48, 48, 8, Scope::Full, true);
  const IrradianceErrors atrium = irradianceErrors(s, "atrium.gltf", 64, 36, 4, Scope::Full);
  const IrradianceErrors cornell1 = irradianceErrors(s, "cornell.gltf", 48, 48, 8, Scope::OneBounce);
  const IrradianceErrors atrium1 = irradianceErrors(s, "atrium.gltf", 64, 36, 4, Scope::OneBounce);
  std::printf("one bounce: cornell rt %.4f legacy %.4f; atrium rt %.4f legacy %.4f\n", cornell1.rt, cornell1.legacy,
              atrium1.rt, atrium1.legacy);
  RecordProperty("cornell_one_bounce_rt_relmse", std::to_string(cornell1.rt));
  RecordProperty("cornell_one_bounce_legacy_relmse", std::to_string(cornell1.legacy));
  RecordProperty("atrium_one_bounce_rt_relmse", std::to_string(atrium1.rt));
  RecordProperty("atrium_one_bounce_legacy_relmse", std::to_string(atrium1.legacy));
  std::printf("irradiance relMSE after 64 frames: cornell rt %.4f legacy %.4f; atrium rt %.4f legacy %.4f\n",
              cornell.rt, cornell.legacy, atrium.rt, atrium.legacy);
  RecordProperty("cornell_rt_relmse", std::to_string(cornell.rt));
  RecordProperty("cornell_legacy_relmse", std::to_string(cornell.legacy));
  RecordProperty("atrium_rt_relmse", std::to_string(atrium.rt));
  RecordProperty("atrium_legacy_relmse", std::to_string(atrium.legacy));
  std::printf("cornell without the radiance cache: rt %.4f\n", cornell.rtNoCache);
  RecordProperty("cornell_no_cache_rt_relmse", std::to_string(cornell.rtNoCache));
  EXPECT_LT(cornell.rt, cornell.legacy);
  EXPECT_LT(atrium.rt, atrium.legacy);
  // The cache switches itself on in the open Cornell box (the light it adds off screen is 40%
  // of the bounced light) and lifts the image from 0.83 to 1.17 of the reference's mean, with
  // cells near the open front holding too much light (docs/accuracy.md, a known defect): 0.355
  // against 0.097 without it. Bounded by legacy's (above) until that is fixed; without the
  // cache, by the figure measured with a margin.
  EXPECT_LT(cornell.rtNoCache, 0.15) << "measured 0.097 (legacy 0.50)";
  EXPECT_LT(atrium.rt, 0.08) << "measured 0.027 (legacy 0.20)";
  EXPECT_LT(cornell1.rt, cornell1.legacy);
  EXPECT_LT(atrium1.rt, atrium1.legacy);
  // Atrium, one bounce: most of the figure is two floor pixels just inside the dark room's
  // doorway (reference ~0.08, where relMSE weighs an error ~1/(r^2 + eps) = 70x): the raw
  // accumulation is right there, the denoiser must not carry the light from outside in.
  EXPECT_LT(cornell1.rt, 0.3) << "measured 0.145 (legacy 0.541)";
  EXPECT_LT(atrium1.rt, 0.1) << "measured 0.025 (legacy 0.236)";
}

// The spatial denoiser's radius follows the GI rays' hit distances. content/translucent_pane.gltf
// with its pane made opaque: a 2 x 2 m roof 1 m over a grey floor, a uniform sky of 1, diffuse
// materials, seen from camera 2 (under the roof, looking across it). The floor under the roof is
// lit by the sky around it; a radius of the scene's scale (a sixth of 20 m) averaged it with the
// open floor a metre away. The centre 8 x 8 pixels' mean after 32 frames against the reference's
// (256 paths a pixel): before the hit distance, 1.275 (through the CLI: 1.236; rtDenoise off:
// 0.975); with the radius at most a quarter of the harmonic mean hit distance, 1.080.
TEST_F(RtTest, TheDenoiserDoesNotCarryTheOpenSkysLightUnderARoof) {
  auto& s = session();
  auto roofed = std::make_unique<scene::Scene>(scene::loadGltf(contentFile("translucent_pane.gltf")));
  for (auto& m : roofed->materials) {
    m.alphaMode = scene::AlphaMode::Opaque;
    m.baseColorFactor.a = 1.0f;
  }
  roofed->contentHash ^= 0x726F6F66ull;  // "roof": not the translucent file's history
  s.installScene(std::move(roofed));
  s.useSceneCamera(2);
  session::Lighting sky = s.lighting();
  sky.sunIrradiance = glm::vec3(0.0f);
  sky.skyRadiance = glm::vec3(1.0f);
  s.setLighting(sky);
  s.settings() = RenderSettings{};
  s.setSize(64, 64);  // after the defaults, which hold the size
  s.settings().materials = MaterialMode::Diffuse;
  s.settings().referenceSamplesPerFrame = 16;
  auto centreMean = [&](const std::string& path, uint32_t frames) {
    s.setPath(path);
    s.resetHistory();
    s.requestBuffer(finalImageOf(path));
    s.renderFrames(frames);
    const auto img = s.buffer(finalImageOf(path)).texels();
    double sum = 0.0;
    for (uint32_t y = 28; y < 36; ++y)
      for (uint32_t x = 28; x < 36; ++x)
        for (uint32_t c = 0; c < 3; ++c) sum += img[(size_t(y) * 64 + x) * 4 + c];
    return sum / (8 * 8 * 3);
  };
  const double reference = centreMean("reference", 16), rt = centreMean("rt", 32);
  s.settings() = RenderSettings{};
  std::printf("under the roof: rt %.4f, reference %.4f (ratio %.3f)\n", rt, reference, rt / reference);
  RecordProperty("rt_over_reference_under_roof", std::to_string(rt / reference));
  EXPECT_NEAR(rt / reference, 1.0, 0.12);
}

// Flicker over a scripted camera path (metrics::flicker: frame-to-frame luminance change
// after reprojection, relative to the mean): the atrium, the camera sliding 2 cm a frame
// sideways; 16 frames to fill the histories, then the mean over 8. The direct path has no
// temporal noise, so its figure is the floor that resampling alone gives; RT's must stay
// within a stated multiple of it, and TAA must lower it. (The spatial denoiser raises it:
// its Poisson disk turns every frame, so the filtered image moves even where the
// accumulated one is steady; measured 0.023 against 0.018 without it.)
TEST_F(RtTest, FlickerOverACameraPathIsBounded) {
  auto& s = session();
  s.loadScene(contentFile("atrium.gltf"));
  const uint32_t w = 96, h = 54;
  auto flickerOf = [&](const char* path, bool denoise, bool taa = false) {
    s.settings() = RenderSettings{};
    s.settings().rtDenoise = denoise;
    s.settings().taa = taa;
    s.setSize(w, h);
    s.setPath(path);
    s.resetHistory();
    s.setFrameIndex(0);
    session::View v = s.view();
    v.position = {-2.0, 2.0, 9.0};
    v.forward = glm::normalize(glm::dvec3(0.1, -0.15, -1.0));
    v.up = {0.0, 1.0, 0.0};
    metrics::Image previous;
    double sum = 0.0;
    int measured = 0;
    for (int f = 0; f < 24; ++f) {
      v.position.x += 0.02;
      s.setView(v);
      s.requestBuffer(lighting::kCompositeHdr);
      s.requestBuffer("gbuffer.motion");
      s.renderFrames(1);
      auto hdr = s.buffer(lighting::kCompositeHdr).texels();
      metrics::Image current = metrics::Image::fromTexels(w, h, 4, hdr);
      if (f >= 16)
        sum += metrics::flicker(previous, current, metrics::Image::fromTexels(w, h, 2, s.buffer("gbuffer.motion").texels())),
            ++measured;
      previous = std::move(current);
    }
    return sum / measured;
  };
  const double direct = flickerOf("direct", true), legacy = flickerOf("legacy", true), rt = flickerOf("rt", true),
               raw = flickerOf("rt", false), rtTaa = flickerOf("rt", true, true);
  std::printf("flicker over the camera path: direct %.4f, legacy %.4f, rt %.4f, rt without spatial denoiser %.4f, "
              "rt with TAA %.4f\n",
              direct, legacy, rt, raw, rtTaa);
  RecordProperty("flicker_direct", std::to_string(direct));
  RecordProperty("flicker_legacy", std::to_string(legacy));
  RecordProperty("flicker_rt", std::to_string(rt));
  RecordProperty("flicker_rt_raw", std::to_string(raw));
  RecordProperty("flicker_rt_taa", std::to_string(rtTaa));
  EXPECT_LT(rt, 4.0 * direct) << "bounded against the resampling floor";
  EXPECT_LT(rtTaa, rt) << "TAA steadies the image";
}

}  // namespace
}  // namespace tl::test
