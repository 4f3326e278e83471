// The Compare panel's estimate of the reference's own noise, against a reference whose
// converged image is known: an accumulation of samples with a known spread around it.
#include "metrics/metrics.h"
#include "session/live_compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace tl::session {
namespace {

constexpr uint32_t kSize = 64;

float truthAt(size_t i) { return 0.5f + 0.3f * std::sin(0.37f * float(i % kSize)) * std::cos(0.21f * float(i / kSize)); }

graph::Readback readback(const std::vector<float>& grey) {
  graph::Readback r{"compare.x", VK_FORMAT_R32G32B32A32_SFLOAT, {kSize, kSize, 1}, {}};
  std::vector<float> rgba(grey.size() * 4, 1.0f);
  for (size_t i = 0; i < grey.size(); ++i) rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = grey[i];
  r.bytes.resize(rgba.size() * sizeof(float));
  std::memcpy(r.bytes.data(), rgba.data(), r.bytes.size());
  return r;
}

metrics::Image image(const std::vector<float>& grey) {
  std::vector<float> rgb(grey.size() * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = grey[i / 3];
  return metrics::Image::fromTexels(kSize, kSize, 3, std::move(rgb));
}

CompareView legacyAgainstRt() {
  CompareView view;
  view.left = std::string("legacy");
  view.right = std::string("rt");
  view.measureFlip = false;
  return view;
}

// Feeds a reference accumulating samples (uniform spread +-0.5 around the truth)
// and two sides 10% and 30% too bright; checks the estimate against the true error of the
// reference after each frame.
TEST(LiveCompare, ReferenceNoiseEstimateFollowsItsTrueError) {
  LiveCompare live(legacyAgainstRt(), "reference", std::nullopt);
  std::vector<float> truth(kSize * kSize), left(truth.size()), right(truth.size()), sum(truth.size(), 0.0f);
  for (size_t i = 0; i < truth.size(); ++i) truth[i] = truthAt(i), left[i] = 1.1f * truth[i], right[i] = 1.3f * truth[i];
  const lighting::FrameKey key;
  live.frameDone("legacy", readback(left), 1.0, key, 0, 1.0f);
  live.frameDone("rt", readback(right), 1.0, key, 0, 1.0f);

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> spread(-0.5f, 0.5f);
  bool trustedEarly = false;
  // Three samples a frame after the first (n = 1, 4, 7, ...): the estimates are taken at
  // uneven ratios (4/1, 10/4, 22/10, ...) and scaled in between.
  for (uint32_t n = 1; n <= 256; n += 3) {
    std::vector<float> mean(truth.size());
    for (size_t i = 0; i < truth.size(); ++i) {
      for (uint32_t k = 0; k < (n == 1 ? 1u : 3u); ++k) sum[i] += truth[i] + spread(rng);
      mean[i] = sum[i] / float(n);
    }
    live.frameDone("reference", readback(mean), 1.0, key, n, 1.0f);
    if (n == 1) {
      EXPECT_FALSE(live.referenceNoise()) << "one state of the sum: nothing to estimate from";
    }
    if (n <= 4) trustedEarly |= live.referenceTrusted();
    if (n == 16 || n == 64 || n == 256) {
      const double actual = metrics::relMse(image(mean), image(truth)).value;
      ASSERT_TRUE(live.referenceNoise()) << n << " samples";
      EXPECT_NEAR(*live.referenceNoise(), actual, 0.25 * actual) << n << " samples";
    }
  }
  // At 1-4 samples the reference's noise (relMSE ~0.3) dwarfs the sides' gap (~0.07); at 256
  // (~0.001) it is well below it.
  EXPECT_FALSE(trustedEarly);
  EXPECT_TRUE(live.referenceTrusted());
}

// A restarted sum (fewer samples than before) forgets the estimate until it has doubled again.
TEST(LiveCompare, ReferenceRestartForgetsTheNoiseEstimate) {
  LiveCompare live(legacyAgainstRt(), "reference", std::nullopt);
  const lighting::FrameKey key;
  std::vector<float> a(kSize * kSize, 0.5f), b(kSize * kSize, 0.52f);
  live.frameDone("reference", readback(a), 1.0, key, 4, 1.0f);
  live.frameDone("reference", readback(b), 1.0, key, 8, 1.0f);
  ASSERT_TRUE(live.referenceNoise());
  live.frameDone("reference", readback(a), 1.0, key, 1, 1.0f);
  EXPECT_FALSE(live.referenceNoise());
}

}  // namespace
}  // namespace tl::session

namespace tl::session {
namespace {

// The reference's standard error as the renderer reads it back (reference.stderr: RGB + samples).
graph::Readback stdErrReadback(const std::vector<float>& grey, uint32_t samples) {
  graph::Readback r = readback(grey);
  std::vector<float> rgba(grey.size() * 4);
  for (size_t i = 0; i < grey.size(); ++i) rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = grey[i], rgba[i * 4 + 3] = float(samples);
  std::memcpy(r.bytes.data(), rgba.data(), r.bytes.size());
  return r;
}

// The panel's verdict against a reference whose noise is known from its running moments: a black
// side against a correct side that is noisier than the reference is at first (its own error, a
// fixed image, about the reference's at 2 samples). As the reference converges, the verdict
// goes from none (too few samples to know the reference's noise) to within noise or the correct
// side closer, and never to the black side closer, while the raw figures do rank black closer at
// the start.
TEST(LiveCompare, NoVerdictUntilSignificantAndNeverForABlackImage) {
  CompareView view = legacyAgainstRt();
  view.left = "black", view.right = "correct";
  LiveCompare live(view, "reference", std::nullopt);
  const size_t count = size_t(kSize) * kSize;
  std::vector<float> truth(count), black(count, 0.0f), correct(count), sum(count, 0.0f), squares(count, 0.0f);
  std::mt19937 rng(11);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::uniform_real_distribution<float> spread(-0.5f, 0.5f);  // the reference's samples: sd 0.29 about the truth
  for (size_t i = 0; i < count; ++i) truth[i] = truthAt(i), correct[i] = truth[i] + 0.2f * normal(rng);
  ASSERT_LT(metrics::relMse(image(correct), image(truth)).value, metrics::relMse(image(black), image(truth)).value)
      << "the correct side is closer in truth";
  const lighting::FrameKey key;
  live.frameDone("black", readback(black), 1.0, key, 0, 1.0f);
  live.frameDone("correct", readback(correct), 1.0, key, 0, 1.0f);
  int rawBlackCloser = 0, blackCloser = 0, verdictsBeforeEnoughSamples = 0;
  bool correctCloser = false;
  for (uint32_t n = 1; n <= 256; ++n) {
    std::vector<float> mean(count), stdErr(count);
    for (size_t i = 0; i < count; ++i) {
      const float x = truth[i] + spread(rng);
      sum[i] += x, squares[i] += x * x;
      mean[i] = sum[i] / float(n);
      const float variance = n > 1 ? std::max(squares[i] - float(n) * mean[i] * mean[i], 0.0f) / float(n - 1) : 0.0f;
      stdErr[i] = std::sqrt(variance / float(n));
    }
    const graph::Readback errors = stdErrReadback(stdErr, n);
    live.frameDone("reference", readback(mean), 1.0, key, n, 1.0f, std::nullopt, &errors);
    const auto e = live.errors();
    ASSERT_EQ(e.size(), 2u);
    ASSERT_TRUE(e[0].relMse && e[1].relMse && e[0].relMseAgainstConverged && e[1].relMseAgainstConverged);
    rawBlackCloser += *e[0].relMse < *e[1].relMse;
    const LiveVerdict verdict = live.verdict();
    if (n < LiveCompare::kMinVerdictSamples) verdictsBeforeEnoughSamples += verdict != LiveVerdict::None;
    blackCloser += verdict == LiveVerdict::LeftCloser;
    correctCloser |= verdict == LiveVerdict::RightCloser;
  }
  std::printf("raw relMSE ranked black closer at %d of 256 reference states; the verdict did %d times\n", rawBlackCloser,
              blackCloser);
  EXPECT_GT(rawBlackCloser, 0) << "the raw figures do rank black closer early (the test can fail)";
  EXPECT_EQ(blackCloser, 0);
  EXPECT_EQ(verdictsBeforeEnoughSamples, 0) << "no verdict before the reference's noise is known";
  EXPECT_TRUE(correctCloser) << "the correct side is found closer once the reference allows";
  EXPECT_TRUE(live.referenceTrusted());
}

}  // namespace
}  // namespace tl::session
