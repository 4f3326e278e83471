// The reference's noise estimate: reference.stderr (the standard error of each pixel's
// estimate, from its running moments) against the spread actually seen between independent
// estimates; the image's relative standard error summed on the GPU against the same sum on the
// CPU; and renders that stop by it (Session::renderReferenceUntilNoise): at the first frame
// that meets the target, or at the cap.
#include "gpu_fixture.h"

#include "lighting/reference/reference_path.h"
#include "session/compare.h"
#include "shared/reference.h"

namespace tl::test {
namespace {

class ReferenceNoiseTest : public RayTracingTest {};

struct Estimate {
  std::vector<float> radiance, stdErr;  // rgba texels
};

// The reference's image and standard error after `spp` samples from the start (16 a frame).
Estimate renderTo(session::Session& s, uint32_t spp) {
  s.settings().referenceSamplesPerFrame = std::min(spp, 16u);
  s.requestBuffer("reference.radiance");
  s.requestBuffer(lighting::kReferenceStdErr);
  s.renderFrames(spp / s.settings().referenceSamplesPerFrame);
  return {s.buffer("reference.radiance").texels(), s.buffer(lighting::kReferenceStdErr).texels()};
}

// The first n1 samples and the n - n1 after them are independent estimates a and c of the same
// pixel, and the image after n samples is b = (n1 a + (n - n1) c) / n (n a pixel's own count:
// adaptive sampling's, decided by its pilot, does not depend on the samples averaged). Their squared
// difference, averaged over pixels and channels, must be what the standard errors say:
// E|a - c|^2 = s^2 (1/n1 + 1/(n - n1)), s^2 = n stderr_b^2 (the per-sample variance, from the
// estimate with the most samples). A standard error of the wrong scale (the samples' own
// spread, or one missing the 1/K^2 of the rounds) is off by a factor of n or more, one off by 2
// fails. The moments are those of the samples seen: where rare paths carry much of the
// variance (cornell: a slot between its light and the ceiling that paths seldom enter, the
// ratio 1.64 at these counts) the estimate runs low until enough of them have been drawn.
TEST_F(ReferenceNoiseTest, StandardErrorMatchesTheSpreadOfIndependentEstimates) {
  auto& s = session();
  const uint32_t n1 = 64, n = 256;
  struct Case {
    const char* scene;
    lighting::MaterialMode materials;
  };
  for (const Case& c : {Case{"lamps.gltf", lighting::MaterialMode::Authored}, Case{"closed_box.gltf", lighting::MaterialMode::Diffuse}}) {
    s.loadScene(contentFile(c.scene));
    s.settings().materials = c.materials;
    s.setPath("reference");
    s.setSize(32, 24);
    s.resetHistory();
    const Estimate a = renderTo(s, n1);
    const Estimate b = renderTo(s, n - n1);
    double measured = 0.0, predicted = 0.0, values = 0.0;
    double samples = 0.0;
    for (size_t i = 0; i < a.radiance.size(); i += 4) {
      // Each pixel's own counts: adaptive sampling gives pixels different ones after its warm-up.
      const double na = a.stdErr[i + 3], nb = b.stdErr[i + 3];
      EXPECT_EQ(na, float(n1)) << "the first 64 samples are uniform (the pilot warms up)";
      samples += nb;
      if (nb <= na) continue;
      for (int k = 0; k < 3; ++k) {
        const double cMean = (nb * double(b.radiance[i + k]) - na * double(a.radiance[i + k])) / (nb - na);
        const double d = double(a.radiance[i + k]) - cMean;
        const double perSample = nb * b.stdErr[i + k] * b.stdErr[i + k];
        measured += d * d;
        predicted += perSample * (1.0 / na + 1.0 / (nb - na));
        values += 1.0;
      }
    }
    EXPECT_NEAR(samples / double(a.radiance.size() / 4), double(n), 0.01 * n) << "the pixels' samples, on average";
    const double ratio = measured / predicted;
    std::printf("%s: mean |a - c|^2 %.4g, from reference.stderr %.4g: ratio %.3f\n", c.scene, measured / values,
                predicted / values, ratio);
    RecordProperty(std::string(c.scene) + "_ratio", std::to_string(ratio));
    EXPECT_GT(predicted, 0.0);
    EXPECT_NEAR(ratio, 1.0, 0.15);
  }
}

// The noise the GPU sums (reference.noise, read back every frame) is the CPU's sum of the same
// images, and is the relative standard error defined in shared/reference.h.
TEST_F(ReferenceNoiseTest, RelativeStandardErrorIsTheImagesOwn) {
  auto& s = session();
  s.setPath("reference");
  s.setSize(40, 30);  // not a multiple of the 16-pixel tiles
  s.resetHistory();
  const Estimate e = renderTo(s, 32);
  const auto noise = s.referenceNoise();
  ASSERT_TRUE(noise.has_value());
  double variance = 0.0, value = 0.0;
  for (size_t i = 0; i < e.radiance.size(); i += 4)
    for (int k = 0; k < 3; ++k) variance += double(e.stdErr[i + k]) * e.stdErr[i + k], value += e.radiance[i + k];
  const double count = 3.0 * double(e.radiance.size() / 4);
  const double rse = std::sqrt(variance / count) / (value / count);
  EXPECT_NEAR(noise->relativeStdError, rse, 1e-4 * rse);
  EXPECT_EQ(noise->fewestSamples, 32u);
  EXPECT_EQ(noise->mostSamples, 32u);
  EXPECT_NEAR(noise->meanSamples, 32.0, 1e-3);
  // One sample a pixel: no variance yet, no noise figure.
  s.resetHistory();
  s.settings().referenceSamplesPerFrame = 1;
  s.renderFrames(1);
  EXPECT_FALSE(s.referenceNoise().has_value());
  s.renderFrames(1);
  EXPECT_TRUE(s.referenceNoise().has_value());
}

// renderReferenceUntilNoise stops at the first frame whose noise meets the target (the frame
// before it did not), and at the cap when the target is out of reach.
TEST_F(ReferenceNoiseTest, UntilNoiseStopsAtTheFirstFrameThatMeetsTheTargetOrAtTheCap) {
  auto& s = session();
  s.loadScene(contentFile("closed_box.gltf"));
  s.settings().materials = lighting::MaterialMode::Diffuse;
  s.setSize(24, 16);
  s.resetHistory();
  session::NoiseTarget target;
  target.relativeStdError = 0.05;
  target.maxSamples = 4096;
  target.samplesPerFrame = 8;
  const session::ReferenceConvergence run = s.renderReferenceUntilNoise(target);
  ASSERT_TRUE(run.reached);
  ASSERT_TRUE(run.noise.has_value());
  EXPECT_LE(run.noise->relativeStdError, target.relativeStdError);
  EXPECT_NEAR(run.noise->meanSamples, double(run.frames * target.samplesPerFrame), 0.01 * run.frames * target.samplesPerFrame)
      << "adaptive sampling spreads each frame's samples, on average samplesPerFrame a pixel";
  EXPECT_EQ(s.path(), "reference");
  std::printf("closed box 24x16: noise %.4f after %u samples\n", run.noise->relativeStdError, run.noise->samplesPerPixel());
  ASSERT_GT(run.frames, 2u);
  s.resetHistory();
  s.renderFrames(run.frames - 1);
  ASSERT_TRUE(s.referenceNoise().has_value());
  EXPECT_GT(s.referenceNoise()->relativeStdError, target.relativeStdError) << "it went on one frame too long";

  s.resetHistory();
  target.relativeStdError = 1e-6;
  target.maxSamples = 64;
  const session::ReferenceConvergence capped = s.renderReferenceUntilNoise(target);
  EXPECT_FALSE(capped.reached);
  ASSERT_TRUE(capped.noise.has_value());
  EXPECT_NEAR(capped.noise->meanSamples, 64.0, 0.64);
  EXPECT_EQ(capped.frames, 8u);
  target.relativeStdError = std::nan("");
  EXPECT_THROW(s.renderReferenceUntilNoise(target), session::SessionError);
}

// compare with a noise target: its reference stops at the target, the report says what it
// reached and with how many samples, and a second run reuses the cached images and figures.
TEST_F(ReferenceNoiseTest, CompareRendersItsReferenceToANoiseTarget) {
  auto& s = session();
  s.loadScene(contentFile("closed_box.gltf"));
  s.settings().materials = lighting::MaterialMode::Diffuse;
  s.setSize(16, 12);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "twinlight-reference-noise-compare";
  std::filesystem::remove_all(dir);
  session::CompareOptions o;
  o.paths = {"direct"};
  o.framesPerPath = 1;
  o.referenceNoise = 0.08;
  o.referenceNoiseCap = 1024;
  o.outDir = dir / "out";
  o.cacheDir = dir / "cache";
  const nlohmann::json first = session::runCompare(s, o);
  const nlohmann::json& noise = first["reference"]["noise"];
  ASSERT_TRUE(noise.contains("relativeStdError")) << first["reference"].dump();
  EXPECT_TRUE(noise["reached"].get<bool>());
  EXPECT_LE(noise["relativeStdError"].get<double>(), 0.08);
  EXPECT_FALSE(first["reference"]["cached"].get<bool>());
  EXPECT_EQ(first["reference"]["spp"], noise["spp"]);
  EXPECT_LT(noise["spp"].get<uint32_t>(), 1024u);
  const nlohmann::json second = session::runCompare(s, o);
  EXPECT_TRUE(second["reference"]["cached"].get<bool>());
  EXPECT_EQ(second["reference"]["noise"], noise);
  EXPECT_EQ(second["paths"][0]["relMSE"], first["paths"][0]["relMSE"]);
  o.referenceNoise = -1.0;
  EXPECT_THROW(session::runCompare(s, o), session::SessionError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tl::test
