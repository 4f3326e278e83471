// Emitter sampling in the reference (reference/path.glsl emitterLight, shared/emitters.h): the
// scene's emissive triangles drawn by power at every scattering event, weighted by the power
// heuristic against the BRDF's rays that hit them. Unbiased: the image converges to what the
// rays alone find, pixel by pixel, within the two images' own standard errors, also for an
// emitter whose texture makes it emit on one side only (the average chooses the triangle, the
// point's texel is what it emits). And the variance at equal samples falls by the factor the
// test states.
#include "gpu_fixture.h"

#include "lighting/reference/reference_path.h"
#include "session/image_io.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

class ReferenceEmittersTest : public RayTracingTest {};

struct Render {
  std::vector<float> radiance, stdErr;
  double meanVariance = 0.0;  // over pixels and channels
};

Render render(session::Session& s, bool emitterSampling, uint32_t spp) {
  s.setPath("reference");
  s.setSize(32, 24);
  s.settings().referenceEmitterSampling = emitterSampling;
  s.settings().referenceSamplesPerFrame = 16;
  s.resetHistory();
  s.renderFrames(spp / 16 - 1);
  s.requestBuffer("reference.radiance");
  s.requestBuffer(lighting::kReferenceStdErr);
  s.renderFrames(1);
  Render r{s.buffer("reference.radiance").texels(), s.buffer(lighting::kReferenceStdErr).texels()};
  double sum = 0.0;
  for (size_t i = 0; i < r.stdErr.size(); i += 4)
    for (int k = 0; k < 3; ++k) sum += double(r.stdErr[i + k]) * r.stdErr[i + k];
  r.meanVariance = sum / (3.0 * double(r.stdErr.size() / 4));
  return r;
}

// How two independent unbiased estimates of one image agree: the mean over pixels and
// channels of (a - b)^2 / (Var a + Var b), 1 when they estimate the same values (a bias
// adds bias^2 / variance), and the image means' difference in their standard errors.
struct Agreement {
  double meanSquaredZ = 0.0, meanZ = 0.0;
};
Agreement agreement(const Render& a, const Render& b, size_t firstRow = 0, size_t rows = ~size_t(0), size_t width = 32) {
  double z2 = 0.0, diff = 0.0, variance = 0.0, n = 0.0;
  for (size_t i = 0; i < a.radiance.size(); i += 4) {
    const size_t row = (i / 4) / width;
    if (row < firstRow || row >= firstRow + rows) continue;
    for (int k = 0; k < 3; ++k) {
      const double d = double(a.radiance[i + k]) - b.radiance[i + k];
      const double v = double(a.stdErr[i + k]) * a.stdErr[i + k] + double(b.stdErr[i + k]) * b.stdErr[i + k];
      if (v > 0.0) z2 += d * d / v, n += 1.0;
      diff += d, variance += v;
    }
  }
  return {z2 / std::max(n, 1.0), diff / std::sqrt(std::max(variance, 1e-30))};
}

// content/cornell.gltf, the light made `scale` times wider and deeper and hung at `height`
// (the file's: 1.99 m, 1 cm under the ceiling), and, for a textured light, an emissive
// texture (`texture`: one row of RGB texels) on it. Written to `dir`.
fs::path cornellWithLight(const fs::path& dir, double scale, double height = 1.99, const std::vector<float>& texture = {}) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto j = nlohmann::json::parse(std::ifstream(contentFile("cornell.gltf")));
  for (auto& n : j["nodes"])
    if (n.value("name", "") == "light_quad") n["scale"] = {scale, 1.0, scale}, n["translation"] = {0.0, height, 0.0};
  if (!texture.empty()) {
    session::writePngRgb(dir / "emission.png", uint32_t(texture.size() / 3), 1, texture);
    j["images"] = nlohmann::json::array({{{"uri", "emission.png"}}});
    j["samplers"] = nlohmann::json::array({{{"magFilter", 9728}, {"minFilter", 9728}}});  // NEAREST: a hard edge
    j["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
    for (auto& m : j["materials"])
      if (m["name"] == "ceiling_light") m["emissiveTexture"] = {{"index", 0}};
  }
  std::ofstream(dir / "cornell.gltf") << j.dump();
  fs::copy_file(contentFile("cornell.bin"), dir / "cornell.bin", fs::copy_options::overwrite_existing);
  return dir / "cornell.gltf";
}

// The factor by which emitter sampling divides the mean variance of a pixel's estimate at 256
// samples, cornell seen from its camera tilted down so the light is out of view (its edges'
// pixels are noisy from the pixel's jitter alone, the same with either estimator).
double varianceFactor(session::Session& s, const char* what) {
  session::View v = s.view();
  v.forward = glm::normalize(glm::dvec3(0.0, -0.5, -1.0));
  s.setView(v);
  const Render sampled = render(s, true, 256), rays = render(s, false, 256);
  const double factor = rays.meanVariance / sampled.meanVariance;
  std::printf("%s, 32x24, 256 spp: mean variance without emitter sampling %.4g, with %.4g (%.1fx less)\n", what,
              rays.meanVariance, sampled.meanVariance, factor);
  return factor;
}

// content/cornell.gltf, a box lit only by its emissive ceiling quad (0.5 x 0.5 m). Over the first
// three scattering events (direct light and two bounces) emitter sampling leaves a small
// fraction of the variance (measured 38x less). Over every bounce less (4.1x): the light is 1 cm
// under the ceiling and emits from both faces (surfaces are two-sided), so the gap between them
// is a bright slot (radiance ~Le) that a path enters rarely, from any surface, and those rare
// paths are most of what remains; hung 0.5 m lower, with no slot, the light leaves 22x less.
TEST_F(ReferenceEmittersTest, CornellVarianceAtEqualSamplesFallsByAnOrderOfMagnitude) {
  auto& s = session();
  const double all = varianceFactor(s, "cornell, every bounce");
  s.settings().referenceBounces = 3;
  const double three = varianceFactor(s, "cornell, three scattering events");
  s.settings().referenceBounces = lighting::RenderSettings{}.referenceBounces;
  const fs::path dir = fs::temp_directory_path() / "twinlight-low-light";
  s.loadScene(cornellWithLight(dir, 1.0, 1.5));
  const double low = varianceFactor(s, "cornell, the light 0.5 m under the ceiling");
  fs::remove_all(dir);
  RecordProperty("variance_factor", std::to_string(all));
  RecordProperty("variance_factor_three_events", std::to_string(three));
  RecordProperty("variance_factor_lowered_light", std::to_string(low));
  EXPECT_GT(three, 15.0);
  EXPECT_GT(low, 10.0);
  EXPECT_GT(all, 2.5);
}

// The scene loaded in `s` rendered at 256 spp with emitter sampling and without it (the BRDF's
// rays alone): the two images agree pixel by pixel within their standard errors, and their
// means within 4 of the difference's.
void expectEmitterSamplingAgreesWithTheRays(session::Session& s, const char* what) {
  const uint32_t spp = 256;
  const Render sampled = render(s, true, spp), rays = render(s, false, spp);
  const Agreement a = agreement(sampled, rays);
  std::printf("%s, 32x24, %u spp: variance %.1fx less; mean z^2 %.3f, image mean difference %.2f sigma\n", what, spp,
              rays.meanVariance / sampled.meanVariance, a.meanSquaredZ, a.meanZ);
  ::testing::Test::RecordProperty("mean_squared_z", std::to_string(a.meanSquaredZ));
  EXPECT_LT(std::abs(a.meanZ), 4.0) << what << ": the image means agree within 4 standard errors";
  EXPECT_NEAR(a.meanSquaredZ, 1.0, 0.25) << what << ": every pixel agrees within its noise";
}

// The same box with the light 1.5 m wide, so that the BRDF's rays find it often enough for
// their estimate's noise to be measured by its own moments: with emitter sampling the same
// image, pixel by pixel, within the two images' standard errors. Counting the emission a ray
// finds at full weight beside the sampled point (no MIS) brightens every lit pixel and fails.
TEST_F(ReferenceEmittersTest, EmitterSamplingConvergesToWhatTheRaysFind) {
  auto& s = session();
  const fs::path dir = fs::temp_directory_path() / "twinlight-wide-light";
  s.loadScene(cornellWithLight(dir, 3.0));
  expectEmitterSamplingAgreesWithTheRays(s, "cornell, 1.5 m light");
  fs::remove_all(dir);
}

// And with an emissive texture that makes the light emit on one half only (the quad's UVs span
// the first two of four texels: white, black): the
// triangles are drawn by the texture's average, the point's texel is what it emits. Taking the
// average as the point's emission (the RT path's approximation) lights the room as if the
// whole panel emitted half as much, and fails.
TEST_F(ReferenceEmittersTest, TexturedEmissionIsWeighedByTheTexelThePointEmits) {
  auto& s = session();
  const fs::path dir = fs::temp_directory_path() / "twinlight-textured-light";
  s.loadScene(cornellWithLight(dir, 3.0, 1.99, {1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f}));
  expectEmitterSamplingAgreesWithTheRays(s, "textured 1.5 m light");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tl::test
