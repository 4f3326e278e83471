// The reference path tracer against closed forms: one scattering event under a uniform sky,
// the plane under a uniform sky, a closed emissive box of Lambertian walls (every bounce:
// L = Le / (1 - rho) exactly), a closed emissive sphere of the full BRDF (its integral equation
// solved on the CPU with a quadrature of the BRDF), the bounce policy on a closed corridor
// (raising the cap changes nothing), and the error falling as 1/sqrt(spp). The white furnace
// is in test_furnace.cpp.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "lighting/reference/reference_path.h"
#include "shared/shading.h"

#include <nlohmann/json.hpp>

#include <array>
#include <fstream>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

// Directional albedo rho(v) = integral of f(v, l) cos(l) over the hemisphere, by quadrature.
double directionalAlbedo(glm::vec3 base, float roughness, float metallic, float nv) {
  using namespace shared;
  SurfaceParams s = tlSurface(base, roughness, metallic);
  glm::vec3 n(0, 0, 1), v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  const int steps = 600;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      double ct = (i + 0.5) / steps, phi = 2 * M_PI * (j + 0.5) / steps, st = std::sqrt(1 - ct * ct);
      glm::vec3 l(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
      sum += double(tlLuminance(tlBrdf(s, n, v, l))) * ct;
    }
  return sum * 2.0 * M_PI / (double(steps) * steps);
}

struct Patch {
  double mean = 0.0;
  size_t nonFinite = 0;
};

// Mean luminance of a size x size patch at the image centre of reference.radiance.
Patch centre(session::Session& s, uint32_t size) {
  const auto& rb = s.buffer("reference.radiance");
  auto t = rb.texels();
  Patch p;
  uint32_t w = rb.extent.width, h = rb.extent.height;
  for (uint32_t y = h / 2 - size / 2; y < h / 2 + size / 2; ++y)
    for (uint32_t x = w / 2 - size / 2; x < w / 2 + size / 2; ++x) {
      const float* c = &t[(size_t(y) * w + x) * 4];
      p.nonFinite += !std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]);
      p.mean += shared::tlLuminance(glm::vec3(c[0], c[1], c[2]));
    }
  p.mean /= double(size) * size;
  return p;
}

void renderReference(session::Session& s, uint32_t size, uint32_t bounces, uint32_t spp) {
  s.setPath("reference");
  s.setSize(size, size);
  s.settings().referenceBounces = bounces;
  s.settings().referenceSamplesPerFrame = std::min(spp, 64u);
  s.requestBuffer("reference.radiance");
  s.resetHistory();
  s.renderFrames(std::max(1u, spp / 64u));
}

class ReferenceTest : public RayTracingTest {};

TEST_F(ReferenceTest, OneScatteringEventUnderUniformSkyReflectsTheAlbedo) {
  auto& s = session();
  s.loadScene(contentFile("furnace.gltf"));
  renderReference(s, 32, 1, 256);
  // Centre of the sphere: n = v. The albedo 0.8 sphere reflects its directional albedo times
  // L: the diffuse layer 0.8 (1 - E_d) plus the specular layer's E_d.
  double expected = directionalAlbedo(glm::vec3(0.8f), 1.0f, 0.0f, 1.0f);
  Patch p = centre(s, 2);
  EXPECT_EQ(p.nonFinite, 0u);
  EXPECT_NEAR(p.mean, expected, 0.01 * expected);
  EXPECT_GT(expected, 0.8);
  EXPECT_LT(expected, 0.81) << "energy conserving: at most the diffuse albedo plus (1 - 0.8) of the specular layer's";
}

TEST_F(ReferenceTest, PlaneUnderUniformSkyIsUnoccluded) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  renderReference(s, 32, 1, 256);
  // The scene camera looks at the origin from (0, 3, 3): n.v = cos 45 deg. Nothing occludes
  // the sky (AO = 1), so the reflected radiance is exactly rho(v) * L.
  double expected = directionalAlbedo(glm::vec3(0.8f), 1.0f, 0.0f, float(std::sqrt(0.5)));
  Patch p = centre(s, 2);
  EXPECT_NEAR(p.mean, expected, 0.02 * expected);
}

// Per-stage ground truth: the irradiance at the primary hit of the open plane is pi L (no
// occluder, nothing to bounce from, the sun excluded), and composite.irradiance (what the
// composite multiplied) holds the same for the direct and the RT path.
TEST_F(ReferenceTest, PlaneIrradianceIsPiLForTheReferenceAndTheComposite) {
  auto& s = session();
  s.loadScene(contentFile("plane.gltf"));
  const uint32_t w = 32, h = 24;
  auto worstError = [&](const std::string& name) {
    auto t = s.buffer(name).texels();
    auto depth = s.buffer("gbuffer.depth").texels();
    const uint32_t c = s.buffer(name).channels();
    const glm::vec3 sky = s.lighting().skyRadiance;
    double worst = 0.0, sum = 0.0;
    size_t surface = 0;
    const uint32_t dw = s.buffer("gbuffer.depth").extent.width;
    auto surfaceAt = [&](size_t i) { return i < depth.size() && depth[i] > 0.0f; };
    for (size_t i = 0; i < depth.size(); ++i) {
      // Interior pixels only: the reference jitters its rays inside the pixel, so a pixel on
      // the plane's silhouette is partly sky there.
      if (!surfaceAt(i) || !surfaceAt(i + 1) || !surfaceAt(i - 1) || !surfaceAt(i + dw) || !surfaceAt(i - dw)) continue;
      ++surface;
      for (int k = 0; k < 3; ++k) {
        double e = std::abs(t[c * i + k] / (shared::kPi * sky[k]) - 1.0);
        worst = std::max(worst, e), sum += e;
      }
    }
    EXPECT_GT(surface, depth.size() / 5) << name;
    return std::pair{worst, sum / std::max<size_t>(1, 3 * surface)};
  };
  // The reference draws no G-buffer of its own to mask with: a direct frame first reads it.
  s.setSize(w, h);
  s.setPath("direct");
  for (std::string_view n : std::initializer_list<std::string_view>{lighting::kCompositeIrradiance, "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(1);
  auto direct = worstError(lighting::kCompositeIrradiance);
  EXPECT_LT(direct.first, 2e-3) << "direct: pi L times AO = 1 (half-float rounding)";

  s.setPath("reference");
  s.settings().referenceBounces = 2;
  s.settings().referenceSamplesPerFrame = 64;
  s.resetHistory();
  for (const char* n : {"reference.irradiance", "reference.ao", "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(4);
  auto reference = worstError("reference.irradiance");
  // Cosine samples of a uniform sky: every sample is pi L, so no noise at all.
  EXPECT_LT(reference.first, 1e-4);
  // Nothing above the plane: the reference AO is exactly 1 on every surface pixel.
  auto ao = s.buffer("reference.ao").texels();
  auto depth = s.buffer("gbuffer.depth").texels();
  size_t occluded = 0;
  for (size_t i = 0; i < depth.size(); ++i) occluded += depth[i] > 0.0f && ao[i] != 1.0f;
  EXPECT_EQ(occluded, 0u);

  s.setPath("rt");
  for (std::string_view n : std::initializer_list<std::string_view>{lighting::kCompositeIrradiance, "gbuffer.depth"}) s.requestBuffer(n);
  s.renderFrames(8);
  auto rt = worstError(lighting::kCompositeIrradiance);
  EXPECT_LT(rt.first, 0.01) << "measured 0.0028 (8 frames accumulated)";
  RecordProperty("rt_composite_irradiance_worst_error", std::to_string(rt.first));
}

// Inside a closed sphere a chord leaves one point and meets another at the same angle to both
// normals, so with uniform emission Le the radiance depends only on that angle and solves
//   L(mu_o) = Le + int_0^1 K(mu_o, mu_i) L(mu_i) dmu_i,   K = mu_i int_0^2pi f(mu_o, mu_i, phi) dphi,
// the kernel taken by a midpoint quadrature of the BRDF's evaluation (nothing of the path
// tracer's sampling or tables' making). Iterated to convergence: the kernel's row sums are the
// directional albedo, below 1. Returns L(1): what a camera at the centre sees.
double closedSphereRadiance(glm::vec3 base, float roughness, float metallic, double Le) {
  using namespace shared;
  SurfaceParams s = tlSurface(base, roughness, metallic);
  const int nm = 96, np = 192;
  auto mu = [&](int i) { return i < nm ? (i + 0.5) / nm : 1.0; };  // node nm is mu = 1
  std::vector<double> kernel(size_t(nm + 1) * nm);
  const glm::vec3 n(0, 0, 1);
  for (int o = 0; o <= nm; ++o) {
    const double mo = mu(o);
    const glm::vec3 v(float(std::sqrt(std::max(0.0, 1.0 - mo * mo))), 0.0f, float(mo));
    for (int i = 0; i < nm; ++i) {
      const double mi = mu(i), si = std::sqrt(1.0 - mi * mi);
      double sum = 0.0;
      for (int j = 0; j < np; ++j) {
        const double phi = 2.0 * M_PI * (j + 0.5) / np;
        const glm::vec3 l(float(si * std::cos(phi)), float(si * std::sin(phi)), float(mi));
        sum += double(tlLuminance(tlBrdf(s, n, v, l)));
      }
      kernel[size_t(o) * nm + i] = mi * sum * (2.0 * M_PI / np) / nm;
    }
  }
  std::vector<double> L(nm + 1, Le), next(nm + 1);
  for (int iteration = 0; iteration < 400; ++iteration) {
    for (int o = 0; o <= nm; ++o) {
      double sum = Le;
      for (int i = 0; i < nm; ++i) sum += kernel[size_t(o) * nm + i] * L[i];
      next[o] = sum;
    }
    L.swap(next);
  }
  return L[nm];
}

// The furnace sphere emitting Le = 1 with base colour 0.5 (authored: the full BRDF), seen from
// its centre, against the integral equation's solution.
TEST_F(ReferenceTest, ClosedEmissiveSphereSolvesItsIntegralEquation) {
  auto& s = session();
  fs::path dir = fs::temp_directory_path() / "twinlight-closed-sphere";
  fs::create_directories(dir);
  auto j = nlohmann::json::parse(std::ifstream(contentFile("furnace.gltf")));
  j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.5, 0.5, 1.0};
  j["materials"][0]["emissiveFactor"] = {1.0, 1.0, 1.0};
  j["materials"][0]["doubleSided"] = true;  // seen from inside: its faces point out
  std::ofstream(dir / "furnace.gltf") << j.dump();
  fs::copy_file(contentFile("furnace.bin"), dir / "furnace.bin", fs::copy_options::overwrite_existing);
  s.loadScene(dir / "furnace.gltf");
  session::View v = s.view();
  v.position = {0.0, 0.0, 0.0};
  v.forward = {0.0, 0.0, -1.0};
  v.up = {0.0, 1.0, 0.0};
  s.setView(v);
  renderReference(s, 16, lighting::RenderSettings{}.referenceBounces, 2048);
  const double expected = closedSphereRadiance(glm::vec3(0.5f), 1.0f, 0.0f, 1.0);
  const double rho = directionalAlbedo(glm::vec3(0.5f), 1.0f, 0.0f, 1.0f);
  Patch p = centre(s, 4);
  EXPECT_EQ(p.nonFinite, 0u);
  std::printf("closed sphere (base 0.5, Le 1): reference %.4f, integral equation %.4f, Le / (1 - rho(1)) %.4f\n", p.mean,
              expected, 1.0 / (1.0 - rho));
  EXPECT_NEAR(p.mean, expected, 0.01 * expected);
  fs::remove_all(dir);
}

// content/closed_box.gltf: six walls of base colour 0.8 emitting Le = 0.2, seen from inside.
// Lambertian walls (the diffuse and clay modes) make the radiance the same everywhere:
// L = Le / (1 - rho) = 1 on every pixel. As authored, the walls' specular layer reflects a
// little more than 0.8 (more at grazing angles): brighter, and no longer uniform, but bounded
// by the Neumann series: Le / (1 - min rho(mu)) <= L <= Le / (1 - max rho(mu)), the directional
// albedo from the quadrature.
TEST_F(ReferenceTest, ClosedLambertianBoxIsLeOverOneMinusRho) {
  auto& s = session();
  s.loadScene(contentFile("closed_box.gltf"));
  const auto& m = s.scene().materials[0];
  const double Le = m.emissiveFactor.x * m.emissiveStrength, rho = m.baseColorFactor.x;
  ASSERT_NEAR(rho, shared::kClayAlbedo, 1e-6) << "the box's walls are as grey as clay: both modes share the closed form";
  const double expected = Le / (1.0 - rho);
  double authoredMean = 0.0;
  for (auto mode : {lighting::MaterialMode::Diffuse, lighting::MaterialMode::Clay, lighting::MaterialMode::Authored}) {
    s.settings().materials = mode;
    renderReference(s, 16, lighting::RenderSettings{}.referenceBounces, 1024);
    auto t = s.buffer("reference.radiance").texels();
    double sum = 0.0, lo = 1e30, hi = 0.0;
    for (size_t i = 0; i < t.size(); i += 4) {
      const double l = shared::tlLuminance(glm::vec3(t[i], t[i + 1], t[i + 2]));
      sum += l, lo = std::min(lo, l), hi = std::max(hi, l);
    }
    const double mean = sum / double(t.size() / 4);
    std::printf("closed box, %s: mean %.4f (pixels %.3f .. %.3f), Le / (1 - rho) = %.4f\n",
                lighting::materialModeName(mode), mean, lo, hi, expected);
    if (mode == lighting::MaterialMode::Authored) {
      authoredMean = mean;
      continue;
    }
    EXPECT_NEAR(mean, expected, 0.01 * expected) << lighting::materialModeName(mode);
    // Each pixel holds 1024 samples of a sum of ~5 emissions: within 10% of the mean.
    EXPECT_GT(lo, 0.9 * expected) << lighting::materialModeName(mode);
    EXPECT_LT(hi, 1.1 * expected) << lighting::materialModeName(mode);
  }
  double rhoMin = 1.0, rhoMax = 0.0;
  for (float mu : {0.02f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const double r = directionalAlbedo(glm::vec3(m.baseColorFactor), m.roughness, m.metallic, mu);
    rhoMin = std::min(rhoMin, r), rhoMax = std::max(rhoMax, r);
  }
  std::printf("closed box, authored: rho(mu) in [%.4f, %.4f]: L in [%.4f, %.4f]\n", rhoMin, rhoMax, Le / (1.0 - rhoMin),
              Le / (1.0 - rhoMax));
  EXPECT_GT(rhoMin, rho) << "the authored walls' specular layer reflects a little more than 0.8";
  EXPECT_GT(authoredMean, 0.995 * Le / (1.0 - rhoMin));
  EXPECT_LT(authoredMean, 1.005 * Le / (1.0 - rhoMax));
}

// The closed box with white walls (Lambert, albedo 1, the diffuse mode) under a cap of N
// scattering events: every event keeps all the light, so a camera path collects Le at each of
// its N + 1 hits (the camera's hit is event 0) and the irradiance pass, which starts at the
// camera's hit, Le from each of N: L = Le (N + 1), E = pi Le N exactly. Every path's weight is
// exactly 1 (cosine sampling of Lambert), so without Russian roulette every pixel would show
// that value with no noise at all; with it (from the fourth event on, survival 0.95 here) paths
// end at random and survivors carry 1/q: the mean stays exact only if the roulette is unbiased,
// and the pixels spread. The same closed form checks how the cap counts events in both passes.
TEST_F(ReferenceTest, RussianRouletteIsUnbiasedInAClosedWhiteBox) {
  auto& s = session();
  fs::path dir = fs::temp_directory_path() / "twinlight-white-box";
  fs::create_directories(dir);
  auto j = nlohmann::json::parse(std::ifstream(contentFile("closed_box.gltf")));
  j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
  std::ofstream(dir / "closed_box.gltf") << j.dump();
  fs::copy_file(contentFile("closed_box.bin"), dir / "closed_box.bin", fs::copy_options::overwrite_existing);
  s.loadScene(dir / "closed_box.gltf");
  const auto& m = s.scene().materials[0];
  const double Le = m.emissiveFactor.x * m.emissiveStrength;
  const uint32_t cap = 12, size = 24;
  s.settings().materials = lighting::MaterialMode::Diffuse;
  s.setPath("reference");
  s.setSize(size, size);
  s.settings().referenceBounces = cap;
  s.settings().referenceSamplesPerFrame = 64;
  s.resetHistory();
  for (int f = 0; f < 16; ++f) {  // 1024 samples; the irradiance accumulates only in frames that read it
    s.requestBuffer("reference.radiance");
    s.requestBuffer("reference.irradiance");
    s.renderFrames(1);
  }
  auto stats = [](const std::vector<float>& t) {
    double sum = 0.0, lo = 1e30, hi = 0.0;
    for (size_t i = 0; i < t.size(); i += 4) {
      const double l = shared::tlLuminance(glm::vec3(t[i], t[i + 1], t[i + 2]));
      sum += l, lo = std::min(lo, l), hi = std::max(hi, l);
    }
    return std::array<double, 3>{sum / double(t.size() / 4), lo, hi};
  };
  const auto radiance = stats(s.buffer("reference.radiance").texels());
  const auto irradiance = stats(s.buffer("reference.irradiance").texels());
  const double expectedL = Le * (cap + 1), expectedE = M_PI * Le * cap;
  std::printf("closed white box, cap %u: radiance mean %.4f (pixels %.3f .. %.3f), Le (N + 1) = %.4f; irradiance "
              "mean %.4f, pi Le N = %.4f\n",
              cap, radiance[0], radiance[1], radiance[2], expectedL, irradiance[0], expectedE);
  EXPECT_NEAR(radiance[0], expectedL, 0.01 * expectedL);
  EXPECT_NEAR(irradiance[0], expectedE, 0.01 * expectedE);
  EXPECT_GT(radiance[2] - radiance[1], 0.01 * expectedL) << "paths end at random: the roulette is on";
  s.settings().materials = lighting::MaterialMode::Authored;
  fs::remove_all(dir);
}

// content/corridor.gltf: a closed white corridor lit through a door. Russian roulette ends
// the paths; the hard cap (RenderSettings::referenceBounces) must not be what ends them: raising
// it to 128 or 256 changes the mean by less than 0.5%. The same seeds draw the same paths, so
// the differences are exactly the light of paths longer than the cap. The old cap of 8 loses
// visibly: the test can tell.
TEST_F(ReferenceTest, BounceCapIsNotVisibleOnAClosedCorridor) {
  auto& s = session();
  s.loadScene(contentFile("corridor.gltf"));
  auto meanAt = [&](uint32_t cap) {
    s.setPath("reference");
    s.setSize(32, 24);
    s.settings().referenceBounces = cap;
    s.settings().referenceSamplesPerFrame = 32;
    s.requestBuffer("reference.radiance");
    s.resetHistory();
    s.renderFrames(2);
    auto t = s.buffer("reference.radiance").texels();
    double sum = 0.0;
    for (size_t i = 0; i < t.size(); i += 4) sum += shared::tlLuminance(glm::vec3(t[i], t[i + 1], t[i + 2]));
    return sum / double(t.size() / 4);
  };
  const uint32_t cap = lighting::RenderSettings{}.referenceBounces;
  EXPECT_GE(cap, 64u);
  const double m8 = meanAt(8), mCap = meanAt(cap), m128 = meanAt(128), m256 = meanAt(256);
  std::printf("corridor mean: cap 8 %.5f, cap %u %.5f, cap 128 %.5f, cap 256 %.5f\n", m8, cap, mCap, m128, m256);
  EXPECT_LT(std::abs(m256 / mCap - 1.0), 0.005);
  EXPECT_LT(std::abs(m128 / mCap - 1.0), 0.005);
  EXPECT_LT(m8, 0.97 * mCap) << "a cap of 8 cuts paths that still carry light";
}

TEST_F(ReferenceTest, ErrorFallsAsOneOverSqrtSpp) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  const uint32_t size = 24;
  auto image = [&](uint32_t spp) {
    renderReference(s, size, 4, spp);
    return s.buffer("reference.radiance").texels();
  };
  // Deterministic seeds: every run draws the same samples, so the nested estimates share
  // their first samples with the 2048-spp truth; the expected ratio per 4x spp is then
  // sqrt((1/n - 1/N) / (1/4n - 1/N)), about 2.0-2.1.
  auto truth = image(2048);
  auto rmse = [&](const std::vector<float>& img) {
    double sum = 0.0;
    for (size_t i = 0; i < img.size(); i += 4)
      for (int c = 0; c < 3; ++c) sum += (img[i + c] - truth[i + c]) * (img[i + c] - truth[i + c]);
    return std::sqrt(sum / (img.size() / 4 * 3));
  };
  double e16 = rmse(image(16)), e64 = rmse(image(64)), e256 = rmse(image(256));
  std::printf("reference RMSE on cornell 24x24 vs 2048 spp: 16 spp %.4f, 64 spp %.4f, 256 spp %.4f\n", e16, e64, e256);
  EXPECT_GT(e16 / e64, 1.6) << e16 << " " << e64;
  EXPECT_LT(e16 / e64, 2.6) << e16 << " " << e64;
  EXPECT_GT(e64 / e256, 1.6) << e64 << " " << e256;
  EXPECT_LT(e64 / e256, 2.6) << e64 << " " << e256;
}

// Deforming meshes: when their vertices move, the reference rebuilds their bottom levels in
// a graph pass (SceneAccel's accel.full.blas.rebuild, then accel.full.tlas). A pose reached by animating must
// then render exactly as the same pose built at load, with the same samples; the pose it left
// renders differently, so the comparison can fail.
TEST_F(ReferenceTest, RebuiltBottomLevelsFollowTheDeformedMeshes) {
  auto& s = session();
  auto image = [&] {
    s.setFrameIndex(0);
    renderReference(s, 32, 2, 16);
    return s.buffer("reference.radiance").texels();
  };
  s.loadScene(contentFile("banners.gltf"));
  s.setAnimationTime(0.0);
  const auto rest = image();
  s.setAnimationTime(0.55);
  const auto animated = image();
  s.loadScene(contentFile("banners.gltf"));
  s.setAnimationTime(0.55);
  const auto loaded = image();
  const double moved = relativeDifferenceRgb(animated, loaded), left = relativeDifferenceRgb(rest, loaded);
  std::printf("reference on the banners at t = 0.55: animated vs loaded %.2e, rest pose vs loaded %.2e\n", moved, left);
  EXPECT_LT(moved, 1e-4);
  EXPECT_GT(left, 100.0 * std::max(moved, 1e-6));
  s.setAnimationTime(0.0);
}


// The radiance split by path depth (lighting::referenceBounceBuffers): traced as the very paths
// of reference.radiance, its four groups sum to it pixel by pixel (float rounding only), and
// the pass that makes them runs only in frames that read one (it costs nothing otherwise).
TEST_F(ReferenceTest, DepthSplitSumsToTheRadianceAndRunsOnDemand) {
  auto& s = session();
  s.loadScene(contentFile("doorway_room.gltf"));
  s.setPath("reference");
  s.setSize(24, 16);
  s.settings().referenceSamplesPerFrame = 8;
  s.resetHistory();
  const auto& groups = lighting::referenceBounceBuffers();
  for (int f = 0; f < 3; ++f) {
    for (const auto& g : groups) s.requestBuffer(g);
    s.requestBuffer("reference.radiance");
    s.renderFrames(1);
  }
  double traceMs = 0.0, splitMs = 0.0;
  for (const auto& t : s.timings()) {
    if (t.pass == "reference.trace") traceMs = t.gpuMs;
    if (t.pass == "reference.bounces") splitMs = t.gpuMs;
  }
  std::printf("last frame: reference.trace %.2f ms, reference.bounces %.2f ms (%.2fx)\n", traceMs, splitMs,
              splitMs / std::max(traceMs, 1e-9));
  EXPECT_GT(splitMs, 0.0) << "the split ran in a frame that read it";
  const auto radiance = s.buffer("reference.radiance").texels();
  std::vector<std::vector<float>> parts;
  for (const auto& g : groups) parts.push_back(s.buffer(g).texels());
  double worst = 0.0, total = 0.0, deepest = 0.0;
  for (size_t i = 0; i < radiance.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (const auto& p : parts) sum += p[i + c];
      worst = std::max(worst, std::abs(sum - radiance[i + c]) / (std::abs(radiance[i + c]) + 1e-6));
      total += radiance[i + c];
      deepest += parts.back()[i + c];
    }
  std::printf("doorway_room depth split: worst relative difference of the sum %.3g; third bounce and more %.1f%%\n",
              worst, 100.0 * deepest / total);
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(total, 0.0);
  EXPECT_GT(deepest, 0.0) << "the room's light reaches the camera after many bounces";

  // Not requested: the pass is culled.
  s.requestBuffer("reference.radiance");
  s.renderFrames(1);
  for (const auto& t : s.timings()) EXPECT_NE(t.pass, "reference.bounces");
}

// The closed box of Lambertian walls (albedo rho = 0.8, every wall emitting Le = 0.2): a camera
// path collects Le at each hit, attenuated by rho per scattering event, so depth k carries
// Le rho^k and L = Le / (1 - rho) = 1. The groups: depths 0 and 1, Le (1 + rho) = 0.36; depth 2,
// Le rho^2 = 0.128; depth 3, Le rho^3 = 0.1024; depth 4 and more, Le rho^4 / (1 - rho) = 0.4096.
TEST_F(ReferenceTest, DepthSplitFollowsTheGeometricSeriesInAClosedBox) {
  auto& s = session();
  s.loadScene(contentFile("closed_box.gltf"));
  const auto& m = s.scene().materials[0];
  const double Le = m.emissiveFactor.x * m.emissiveStrength, rho = m.baseColorFactor.x;
  s.settings().materials = lighting::MaterialMode::Diffuse;
  s.setPath("reference");
  s.setSize(24, 24);
  s.settings().referenceSamplesPerFrame = 64;
  s.resetHistory();
  const auto& groups = lighting::referenceBounceBuffers();
  for (int f = 0; f < 4; ++f) {  // 256 samples per pixel
    for (const auto& g : groups) s.requestBuffer(g);
    s.renderFrames(1);
  }
  const double expected[] = {Le * (1.0 + rho), Le * rho * rho, Le * rho * rho * rho,
                             Le * std::pow(rho, 4.0) / (1.0 - rho)};
  for (size_t g = 0; g < groups.size(); ++g) {
    const auto t = s.buffer(groups[g]).texels();
    double mean = 0.0;
    for (size_t i = 0; i < t.size(); i += 4) mean += shared::tlLuminance(glm::vec3(t[i], t[i + 1], t[i + 2]));
    mean /= double(t.size() / 4);
    std::printf("closed box, %s: mean %.4f, Le rho^k summed %.4f\n", groups[g].c_str(), mean, expected[g]);
    // Depths up to 3 carry no noise (every path weighs exactly rho per event before the roulette
    // starts); the last group has the roulette's.
    const double tolerance = g + 1 < groups.size() ? 0.005 : 0.02;
    EXPECT_NEAR(mean, expected[g], tolerance * expected[g]) << groups[g];
  }
  s.settings().materials = lighting::MaterialMode::Authored;
}

}  // namespace
}  // namespace tl::test
