// Scale-free rendering: every content scene drawn at x0.01, x1 and x100 (cameras, lights and
// every length scaled with it, scene/scene_scale.h) is the same picture in every lighting
// path and plugin, up to noise. Light transport with a sun, a sky, emitters and area lights of
// fixed radiance and point lights whose intensity grows with the square of the scale has no
// length in it, so any difference between the scales is a constant in metres somewhere.
//
// Measured per scene and path, against the x1 image from frame index 0: the x1 image from
// another frame index (another draw of every random number: the noise between two seeds), and
// the x0.01 and x100 images from frame index 0. The scaled images must hold the x1 mean within
// 2% and be no further from it (relMSE_norm) than the other seed is, with a floor for paths
// without noise (there the two seeds are the same image).
#include "gpu_fixture.h"

#include "scene/scene_scale.h"
#include "session/lighting_file.h"

#include <cstdio>
#include <filesystem>

namespace tl::test {
namespace {

std::vector<std::string> contentSceneNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(TWINLIGHT_CONTENT_DIR, ec)) {
    const auto ext = e.path().extension();
    if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb")) names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The scene and its lighting sidecar, `factor` times larger.
void loadScaled(session::Session& s, const std::filesystem::path& file, double factor) {
  std::unique_ptr<scene::Scene> parsed = session::Session::parseScene(file);
  session::Lighting lighting = session::sceneLighting(*parsed, session::Lighting{});
  const auto sidecar = session::lightingSidecarPath(file);
  if (std::filesystem::exists(sidecar)) lighting = session::readLightingFile(sidecar, lighting);
  scene::scaleScene(*parsed, factor);
  for (scene::Light& l : lighting.lights) scene::scaleLight(l, factor);
  s.installScene(std::move(parsed));
  s.setLighting(lighting);
}

constexpr uint32_t kWidth = 48, kHeight = 27, kFrames = 6;

// The final HDR image (RGBA) of `path` after kFrames frames from a fresh history, its noise
// drawn from frame index `seed` on.
std::vector<float> render(session::Session& s, const std::string& path, uint64_t seed) {
  s.setPath(path);
  s.setSize(kWidth, kHeight);
  s.setFrameIndex(seed);
  s.resetHistory();
  s.renderFrames(kFrames - 1);
  s.requestBuffer(finalImageOf(path));
  s.renderFrames(1);
  return s.buffer(finalImageOf(path)).texels();
}

double meanLuminance(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) sum += 0.2126 * rgba[i] + 0.7152 * rgba[i + 1] + 0.0722 * rgba[i + 2];
  return sum / double(rgba.size() / 4);
}

// Mean squared RGB difference over the square of the reference's mean luminance (the
// exposure-normalised relMSE of compare, without its per-pixel weighting).
double relMseNorm(const std::vector<float>& a, const std::vector<float>& b) {
  const double m = std::max(meanLuminance(b), 1e-30);
  double sum = 0.0;
  for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum += double(a[i + c] - b[i + c]) * double(a[i + c] - b[i + c]);
  return sum / double(3 * (a.size() / 4)) / (m * m);
}

class ScaleInvarianceTest : public GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(ScaleInvarianceTest, EveryPathDrawsTheSameImageAtAHundredthAndAHundredTimesTheSize) {
  auto& s = session();
  const std::filesystem::path file = contentFile(GetParam().c_str());
  for (const session::PathInfo& info : s.paths()) {
    if (!info.available) continue;
    const std::string& path = info.name;
    loadScaled(s, file, 1.0);
    const std::vector<float> base = render(s, path, 0);
    const std::vector<float> otherSeed = render(s, path, 1u << 20);
    const double mean = meanLuminance(base);
    // Two seeds' difference is the noise a scaled image may show; a noise-free path gives the
    // same image twice, and then only rounding may part the scales (1% RMS of the mean).
    const double noise = std::max(relMseNorm(otherSeed, base), 1e-4);
    for (double factor : {0.01, 100.0}) {
      loadScaled(s, file, factor);
      const std::vector<float> scaled = render(s, path, 0);
      const double scaledMean = meanLuminance(scaled), difference = relMseNorm(scaled, base);
      std::printf("scale %-26s %-9s x%-5g mean %.5g / %.5g  relMSE_norm %.2e (seeds %.2e)\n", GetParam().c_str(),
                  path.c_str(), factor, scaledMean, mean, difference, noise);
      if (!(mean > 0.0)) {
        EXPECT_EQ(scaledMean, 0.0) << path << " x" << factor << ": light in a black image";
        continue;
      }
      EXPECT_NEAR(scaledMean / mean, 1.0, 0.02) << path << " x" << factor << ": the mean moved";
      EXPECT_LE(difference, noise) << path << " x" << factor << ": the image differs beyond the noise between two seeds";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ContentScenes, ScaleInvarianceTest, ::testing::ValuesIn(contentSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = std::filesystem::path(info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace tl::test
