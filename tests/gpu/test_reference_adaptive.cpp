// Adaptive sampling in the reference (shared/reference.h, reference/trace.rgen): each frame's
// samples drawn in proportion to each pixel's noise as an independent pilot measures it. The
// image stays unbiased: over the image and over every region it agrees with a uniform render
// of the same samples within the noise of their difference; and the allocation that decides by
// the estimate's own samples (kRefAdaptiveOwn, the shortcut the pilot exists to avoid) is
// caught by the same check. The samples do go where the noise is; whether the image's error at
// equal samples falls is measured, not asserted (on this scene it does not: see below).
#include "gpu_fixture.h"

#include "lighting/reference/reference_path.h"
#include "shared/reference.h"

#include <algorithm>

namespace tl::test {
namespace {

class ReferenceAdaptiveTest : public RayTracingTest {};

constexpr uint32_t kWidth = 32, kHeight = 24;

struct Render {
  std::vector<float> radiance, stdErr, allocation;  // rgba texels
};

// The scene loaded in `s` with `adaptive` (shared/reference.h kRefAdaptive*) to `spp` samples a
// pixel on average, 16 a frame.
Render render(session::Session& s, uint32_t adaptive, uint32_t spp) {
  s.setPath("reference");
  s.setSize(kWidth, kHeight);
  s.settings().referenceAdaptive = adaptive;
  s.settings().referenceSamplesPerFrame = 16;
  s.resetHistory();
  s.renderFrames(spp / 16 - 1);
  s.requestBuffer("reference.radiance");
  s.requestBuffer(lighting::kReferenceStdErr);
  s.requestBuffer(lighting::kReferenceAllocation);
  s.renderFrames(1);
  return {s.buffer("reference.radiance").texels(), s.buffer(lighting::kReferenceStdErr).texels(),
          s.buffer(lighting::kReferenceAllocation).texels()};
}

// How far an image a is from a uniform render u of n samples a pixel, in the noise of their
// difference. The samples are numbered alike (a pixel's k-th sample is the same path in both),
// so a pixel's a, of n_a samples, and u share min(n_a, n) samples: where n_a does not depend on
// the values, Var(a - u) = s^2 |1/n_a - 1/n| (s^2 the per-sample variance, from u's standard
// error: n stderr^2). The largest |z| of a region's mean difference, per channel, over the
// image's 8 x 8 regions and over the whole image.
struct Departure {
  double image = 0.0;    // largest |z| of the image's mean, over the channels
  double regions = 0.0;  // largest |z| of a region's mean, over regions and channels
};
Departure departure(const Render& a, const Render& u, uint32_t n) {
  constexpr uint32_t kRegion = 8;
  const uint32_t columns = kWidth / kRegion, rows = kHeight / kRegion;
  std::vector<double> diff(3 * (columns * rows + 1), 0.0), variance(diff.size(), 0.0);
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = 4 * (size_t(y) * kWidth + x);
      const double na = a.stdErr[i + 3];
      const size_t region = (y / kRegion) * columns + x / kRegion, whole = columns * rows;
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.radiance[i + c]) - u.radiance[i + c];
        const double perSample = double(n) * u.stdErr[i + c] * u.stdErr[i + c];
        const double v = perSample * std::abs(1.0 / na - 1.0 / double(n));
        for (size_t r : {region, whole}) diff[3 * r + c] += d, variance[3 * r + c] += v;
      }
    }
  Departure out;
  for (size_t r = 0; r <= columns * rows; ++r)
    for (int c = 0; c < 3; ++c) {
      const double z = std::abs(diff[3 * r + c]) / std::sqrt(std::max(variance[3 * r + c], 1e-30));
      double& worst = r == columns * rows ? out.image : out.regions;
      worst = std::max(worst, z);
    }
  return out;
}

// Unbiased as far as the check can tell: the image's means within 4 standard errors of the
// difference, and every region's within 4.5 (36 region means: a chance |z| above 4.5 among
// them has odds of about 1 in 4000).
bool agrees(const Departure& d) { return d.image < 4.0 && d.regions < 4.5; }

// Sum over pixels and channels of (a - b)^2.
double squaredDistance(const Render& a, const Render& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.radiance.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum += double(a.radiance[i + c] - b.radiance[i + c]) * (a.radiance[i + c] - b.radiance[i + c]);
  return sum;
}

// content/cornell.gltf lit by its ceiling quad found by the BRDF's rays alone (no emitter
// sampling): most of a pixel's variance comes from rare paths into the slot between the light
// and the ceiling, the hard case for an allocation that trusts the samples it has seen. 512
// samples a pixel with the pilot's allocation, with the estimate's own and uniformly (all 16 a
// frame; adaptive from the fifth frame on), against 2048 uniform samples for the error.
TEST_F(ReferenceAdaptiveTest, StaysUnbiasedWhereTheEstimatesOwnSamplesWouldBiasIt) {
  auto& s = session();
  s.settings().referenceEmitterSampling = false;
  const uint32_t n = 512;
  const Render uniform = render(s, shared::kRefAdaptiveOff, n);
  const Render pilot = render(s, shared::kRefAdaptivePilot, n);
  const Render own = render(s, shared::kRefAdaptiveOwn, n);
  const Render converged = render(s, shared::kRefAdaptiveOff, 4 * n);

  // The samples went where the noise is: counts that differ, the same mean.
  double fewest = 1e30, most = 0.0, total = 0.0;
  for (size_t i = 0; i < pilot.stdErr.size(); i += 4) {
    fewest = std::min<double>(fewest, pilot.stdErr[i + 3]);
    most = std::max<double>(most, pilot.stdErr[i + 3]);
    total += pilot.stdErr[i + 3];
  }
  const double mean = total / double(kWidth * kHeight);
  std::printf("pilot allocation after %u spp: fewest %.0f, most %.0f, mean %.1f samples a pixel\n", n, fewest, most, mean);
  EXPECT_NEAR(mean, double(n), 0.03 * n) << "the budget is spent, no more";
  EXPECT_GT(most, 4.0 * fewest) << "the samples follow the noise";

  const Departure fromPilot = departure(pilot, uniform, n), fromOwn = departure(own, uniform, n);
  // Measured (lavapipe, 2026-12-05): pilot image 0.63, worst region 1.42; own samples image 8.33,
  // worst region 5.12. Fewest 120, most 6622, mean 500.5 samples a pixel (the 16x cap's loss).
  std::printf("|z| from the uniform image: pilot image %.2f, worst region %.2f; own samples image %.2f, worst region %.2f\n",
              fromPilot.image, fromPilot.regions, fromOwn.image, fromOwn.regions);
  RecordProperty("pilot_image_z", std::to_string(fromPilot.image));
  RecordProperty("own_image_z", std::to_string(fromOwn.image));
  EXPECT_TRUE(agrees(fromPilot)) << "the image's mean and every region's agree with the uniform image's";
  EXPECT_FALSE(agrees(fromOwn)) << "deciding by the estimate's own samples is biased, and the same check sees it";

  // The error at equal samples, against the converged image (minus the part it shares with
  // it: both sides carry its own variance alike, sum s^2 / 4n).
  const double uniformError = squaredDistance(uniform, converged), pilotError = squaredDistance(pilot, converged);
  std::printf("squared error against %u uniform spp: uniform %.4g, pilot %.4g (%.2fx)\n", 4 * n, uniformError, pilotError,
              uniformError / pilotError);
  // Not asserted: on this scene the allocation loses (measured 0.58x: uniform 3.237, pilot 5.614).
  // Its pilot, 1 in 16 of the samples, rarely draws the slot's paths, so most pixels look quiet
  // and get the floor's share (fewest 120 samples against 512): their variance, which those rare
  // paths carry, grows. Why adaptive sampling is off by default (docs/design/reference.md).
  RecordProperty("error_ratio", std::to_string(uniformError / pilotError));
}

// The depth split traces the trace pass's own paths under adaptive sampling too: its four
// images sum to reference.radiance.
TEST_F(ReferenceAdaptiveTest, DepthSplitFollowsTheAllocation) {
  auto& s = session();
  s.setPath("reference");
  s.setSize(kWidth, kHeight);
  s.settings().referenceSamplesPerFrame = 16;
  s.settings().referenceAdaptive = shared::kRefAdaptivePilot;
  s.resetHistory();
  const auto& groups = lighting::referenceBounceBuffers();
  for (int frame = 0; frame < 8; ++frame) {
    for (const auto& g : groups) s.requestBuffer(g);
    s.requestBuffer("reference.radiance");
    s.requestBuffer(lighting::kReferenceAllocation);
    s.renderFrames(1);
  }
  const auto radiance = s.buffer("reference.radiance").texels();
  const auto allocation = s.buffer(lighting::kReferenceAllocation).texels();
  std::vector<float> sum(radiance.size(), 0.0f);
  for (const auto& g : groups) {
    const auto t = s.buffer(g).texels();
    for (size_t i = 0; i < t.size(); ++i) sum[i] += t[i];
  }
  bool uneven = false;
  for (size_t i = 0; i < allocation.size(); i += 4) uneven |= allocation[i] != 16.0f;
  EXPECT_TRUE(uneven) << "the last frame's counts differ between pixels";
  EXPECT_LT(relativeDifferenceRgb(sum, radiance), 1e-4);
}

}  // namespace
}  // namespace tl::test
