// Scale-free rendering: every content scene drawn at x0.01, x1 and x100 (cameras, lights and
// every length scaled with it, scene/scene_scale.h) is the same picture in every lighting
// path and plugin, up to noise. Light transport with a sun, a sky, emitters and area lights of
// fixed radiance and point lights whose intensity grows with the square of the scale has no
// length in it, so any difference between the scales is a constant in metres somewhere.
//
// Measured per scene and path, against the x1 image from frame index 0: the x1 image from
// two other draws of every random number (the noise between two seeds: frames from another
// frame index, the camera moved across and up, then down and back, by a thousandth of a pixel,
// so that pixels whose centre falls exactly on an edge (a nearest-filtered texel's, a
// shadow-map texel's) land on either side, as rounding at another scale may let them; the
// reference, whose samples are numbered from its own start, takes the next frames' samples),
// and the x0.01 and x100 images from frame index 0. The scaled images must hold the x1 mean
// within 2% (or within three times the two seeds' difference where the noise is larger) and
// be no further from it (relMSE_norm) than the other seeds are (within 1.5x: one pair's mean
// square over 1,296 correlated pixels is itself uncertain by tens of percent; the constants in
// metres this test found were 3x to 400x above it), with a floor for paths without noise
// (there the seeds give the same image). A failed comparison leaves its images in
// $TMPDIR/scale_invariance/ for a look.
//
// One test instance per scene and path (ContentScenes/ScaleInvarianceTest.*/grove_legacy): the
// slow shards share them out, where one instance per scene looping over the paths made a
// shard of grove alone (79 s, legacy's voxelization of its foliage 44 s of it). Each instance
// does what one turn of that loop did: the scene loaded at x1, x0.01 and x100 for its path.
#include "gpu_fixture.h"

#include "lighting/lighting_path.h"

#include "scene/scene_scale.h"
#include "session/image_io.h"
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

// Every lighting path this build knows (the built-ins and the plugins), by name, without a
// device: the registry's factories are cheap to call.
std::vector<std::string> lightingPathNames() {
  std::vector<std::string> names;
  for (lighting::LightingPathFactory make : lighting::lightingPathRegistry()) names.push_back(make()->name());
  return names;
}

struct SceneAndPath {
  std::string scene, path;
};

std::vector<SceneAndPath> contentScenesAndPaths() {
  std::vector<SceneAndPath> out;
  for (const std::string& scene : contentSceneNames())
    for (const std::string& path : lightingPathNames()) out.push_back({scene, path});
  return out;
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

// The same image from other random numbers, `draw` 0 or 1: frames from another frame index,
// the camera moved across and up (draw 0) or down and back (draw 1) by a thousandth of a pixel;
// for the reference (its sample k is the same draw whatever the frame) the mean of the
// kFrames samples after the first (draw + 1) kFrames, from two running means.
std::vector<float> renderOtherSeed(session::Session& s, const session::PathInfo& info, int draw) {
  if (info.capabilities.isReference) {
    const std::string_view image = finalImageOf(info.name);
    s.setPath(info.name);
    s.setSize(kWidth, kHeight);
    s.setFrameIndex(0);
    s.resetHistory();
    s.renderFrames(uint32_t(draw + 1) * kFrames - 1);
    s.requestBuffer(image);
    s.renderFrames(1);
    const std::vector<float> before = s.buffer(image).texels();
    s.renderFrames(kFrames - 1);
    s.requestBuffer(image);
    s.renderFrames(1);
    std::vector<float> after = s.buffer(image).texels();
    const float n = float(draw + 2), m = float(draw + 1);
    for (size_t i = 0; i < after.size(); ++i) after[i] = n * after[i] - m * before[i];
    return after;
  }
  const session::View view = s.view();
  session::View moved = view;
  const glm::dvec3 right = glm::normalize(glm::cross(view.forward, view.up));
  const glm::dvec3 centre = s.scene().bounds.valid() ? s.scene().bounds.center() : view.position + view.forward;
  const double depth = std::max(glm::dot(centre - view.position, view.forward), 1e-30);
  const double pixel = view.orthographic ? 2.0 * view.orthoHalfHeight / kHeight
                                         : 2.0 * depth * std::tan(0.5 * view.yfovRadians) / kHeight;
  const double side = draw == 0 ? 1.0 : -1.0;
  moved.position += (right + glm::normalize(glm::cross(right, view.forward))) * (side * 1e-3 * pixel);
  s.setView(moved);
  std::vector<float> image = render(s, info.name, uint64_t(draw + 1) << 20);
  s.setView(view);
  return image;
}

void writeForALook(const std::string& name, const std::vector<float>& rgba) {
  std::vector<float> rgb;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) rgb.insert(rgb.end(), {rgba[i], rgba[i + 1], rgba[i + 2]});
  const auto dir = std::filesystem::temp_directory_path() / "scale_invariance";
  std::filesystem::create_directories(dir);
  session::writeExrRgb(dir / (name + ".exr"), kWidth, kHeight, rgb);
}

double meanLuminance(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) sum += 0.2126 * rgba[i] + 0.7152 * rgba[i + 1] + 0.0722 * rgba[i + 2];
  return sum / double(rgba.size() / 4);
}

// Mean squared RGB difference over the square of mean luminance `m` (the exposure-normalised
// relMSE of compare, without its per-pixel weighting).
double relMseNorm(const std::vector<float>& a, const std::vector<float>& b, double m) {
  m = std::max(m, 1e-30);
  double sum = 0.0;
  for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum += double(a[i + c] - b[i + c]) * double(a[i + c] - b[i + c]);
  return sum / double(3 * (a.size() / 4)) / (m * m);
}

class ScaleInvarianceTest : public GpuTest, public ::testing::WithParamInterface<SceneAndPath> {};

TEST_P(ScaleInvarianceTest, EveryPathDrawsTheSameImageAtAHundredthAndAHundredTimesTheSize) {
  auto& s = session();
  const std::string& sceneName = GetParam().scene;
  const std::string& path = GetParam().path;
  const std::filesystem::path file = contentFile(sceneName.c_str());
  const std::vector<session::PathInfo> paths = s.paths();
  const auto info = std::find_if(paths.begin(), paths.end(), [&](const session::PathInfo& p) { return p.name == path; });
  ASSERT_NE(info, paths.end()) << "the session has no path `" << path << "`";
  if (!info->available) GTEST_SKIP() << path << ": " << info->unavailableReason;
  loadScaled(s, file, 1.0);
  const std::vector<float> base = render(s, path, 0);
  const std::vector<float> otherSeed = renderOtherSeed(s, *info, 0), thirdSeed = renderOtherSeed(s, *info, 1);
  const double mean = meanLuminance(base);
  // Two seeds' difference is the noise a scaled image may show (the larger of two pairs; the
  // pair moved opposite ways holds every edge pixel); a noise-free path gives the same image,
  // and then only rounding may part the scales (1% RMS of the mean).
  const double noise = std::max({relMseNorm(otherSeed, base, mean), relMseNorm(otherSeed, thirdSeed, mean), 1e-4});
  const double meanNoise = mean > 0.0 ? std::abs(meanLuminance(otherSeed) / mean - 1.0) : 0.0;
  for (double factor : {0.01, 100.0}) {
    loadScaled(s, file, factor);
    const std::vector<float> scaled = render(s, path, 0);
    const double scaledMean = meanLuminance(scaled), difference = relMseNorm(scaled, base, mean);
    std::printf("scale %-26s %-9s x%-5g mean %.5g / %.5g  relMSE_norm %.2e (seeds %.2e)\n", sceneName.c_str(),
                path.c_str(), factor, scaledMean, mean, difference, noise);
    if (!(mean > 0.0)) {
      EXPECT_EQ(scaledMean, 0.0) << path << " x" << factor << ": light in a black image";
      continue;
    }
    const bool meanHeld = std::abs(scaledMean / mean - 1.0) <= std::max(0.02, 3.0 * meanNoise);
    EXPECT_TRUE(meanHeld) << path << " x" << factor << ": the mean moved by " << scaledMean / mean - 1.0
                          << " (two seeds: " << meanNoise << ")";
    EXPECT_LE(difference, 1.5 * noise) << path << " x" << factor << ": the image differs beyond the noise between two seeds";
    if (!meanHeld || difference > 1.5 * noise) {
      const std::string stem = std::filesystem::path(sceneName).stem().string() + "_" + path;
      writeForALook(stem + "_x1", base);
      writeForALook(stem + "_x1_other_seed", otherSeed);
      writeForALook(stem + (factor < 1.0 ? "_x0.01" : "_x100"), scaled);
    }
  }
}

// Instances named scene_path (grove_legacy, cornell_rt).
INSTANTIATE_TEST_SUITE_P(ContentScenes, ScaleInvarianceTest, ::testing::ValuesIn(contentScenesAndPaths()),
                         [](const ::testing::TestParamInfo<SceneAndPath>& info) {
                           std::string name = std::filesystem::path(info.param.scene).stem().string() + "_" + info.param.path;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace tl::test
