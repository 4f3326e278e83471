// The environment map on the CPU (scene/environment_map.h, shared/environment.h): its
// directions, its importance table and its spherical-harmonic projection against closed forms.
#include "../common/temp_dir.h"
#include "scene/environment_map.h"
#include "scene/scene.h"
#include "shared/environment.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

namespace tl::scene {
namespace {

using tl::test::contentFile;
using tl::test::TempDir;

namespace fs = std::filesystem;


EnvironmentMap uniform(uint32_t w, uint32_t h, glm::vec3 l) { return makeEnvironmentMap(w, h, std::vector<glm::vec3>(size_t(w) * h, l)); }

TEST(EnvironmentMap, DirectionsRoundTripAndTheCentreLooksForward) {
  const glm::vec3 forward = shared::tlEquirectDirection(glm::vec2(0.5f, 0.5f));
  EXPECT_NEAR(forward.z, -1.0f, 1e-6f);
  EXPECT_NEAR(shared::tlEquirectDirection(glm::vec2(0.75f, 0.5f)).x, 1.0f, 1e-6f);  // u grows towards +X
  EXPECT_NEAR(shared::tlEquirectDirection(glm::vec2(0.3f, 0.0f)).y, 1.0f, 1e-6f);   // row 0: the zenith
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.001f, 0.999f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 uv(u(rng), u(rng));
    const glm::vec2 back = shared::tlEquirectUv(shared::tlEquirectDirection(uv));
    EXPECT_NEAR(back.x, uv.x, 2e-5f);
    EXPECT_NEAR(back.y, uv.y, 2e-5f);
    const glm::vec2 cs(std::cos(1.1f), std::sin(1.1f));
    const glm::vec3 d = shared::tlEquirectDirection(uv);
    const glm::vec3 turned = shared::tlEnvWorldToMap(shared::tlEnvMapToWorld(d, cs), cs);
    EXPECT_NEAR(glm::length(turned - d), 0.0f, 1e-5f);
  }
  // A quarter turn about +Y (counter-clockwise from above) takes -Z (the map's centre) to -X.
  const glm::vec3 q = shared::tlEnvMapToWorld(forward, glm::vec2(0.0f, 1.0f));
  EXPECT_NEAR(q.x, -1.0f, 1e-6f);
}

// A map of a uniform sky L = 0.3 and a sun disc of 2 degrees radius, 5000 times brighter, at a
// known direction (to texel accuracy: the disc is every texel whose centre lies within it).
TEST(EnvironmentMap, ASunIsSeparatedFromItsSkyWithItsLightDirectionAndSize) {
  const uint32_t w = 512, h = 256;
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(0.4, 0.6, -0.5));
  const double radius = glm::radians(2.0);
  std::vector<glm::vec3> t(size_t(w) * h, glm::vec3(0.3f));
  const EnvironmentMap probe = makeEnvironmentMap(w, h, t);
  double sunOmega = 0.0;
  glm::dvec3 sunSum(0.0);
  for (uint32_t r = 0; r < h; ++r)
    for (uint32_t c = 0; c < w; ++c) {
      const glm::dvec3 d(shared::tlEquirectDirection(glm::vec2((c + 0.5f) / w, (r + 0.5f) / h)));
      if (glm::dot(d, toSun) < std::cos(radius)) continue;
      t[size_t(r) * w + c] = glm::vec3(1500.0f);
      sunOmega += environmentTexelSolidAngle(probe, r);
      sunSum += d * environmentTexelSolidAngle(probe, r);
    }
  const EnvironmentMap map = makeEnvironmentMap(w, h, t);
  const auto split = separateEnvironmentSun(map);
  ASSERT_TRUE(split.has_value());
  // Its light above the sky behind it: (1500 - 0.3) x its solid angle, exactly (the texels' own).
  EXPECT_NEAR(split->sun.irradiance.r, (1500.0 - 0.3) * sunOmega, 1e-4 * 1500.0 * sunOmega);
  EXPECT_GT(glm::dot(split->sun.direction, glm::normalize(sunSum)), std::cos(glm::radians(0.01)));
  EXPECT_GT(glm::dot(split->sun.direction, toSun), std::cos(glm::radians(0.3)));  // the disc's texel grid
  EXPECT_NEAR(glm::degrees(split->sun.angularRadius), 2.0, 0.15);
  // The sky keeps the rest: uniform 0.3 everywhere, and sun plus sky hold the map's light.
  for (const glm::vec3& texel : split->sky->radiance) ASSERT_NEAR(texel.r, 0.3f, 1e-6f);
  const double before = 4.0 * M_PI * map.meanRadiance.r, after = 4.0 * M_PI * split->sky->meanRadiance.r + split->sun.irradiance.r;
  EXPECT_NEAR(after / before, 1.0, 1e-6);
}

TEST(EnvironmentMap, AnOvercastMapOrADimHighlightHasNoSun) {
  const uint32_t w = 128, h = 64;
  std::vector<glm::vec3> t(size_t(w) * h);
  for (uint32_t r = 0; r < h; ++r)
    for (uint32_t c = 0; c < w; ++c) t[size_t(r) * w + c] = glm::vec3(0.2f + 0.8f * float(h - r) / float(h));
  EXPECT_FALSE(separateEnvironmentSun(makeEnvironmentMap(w, h, t)).has_value()) << "an overcast gradient";
  // One texel 100 times the mean, but holding far less than a fifth of the light.
  t[size_t(10) * w + 20] = glm::vec3(60.0f);
  EXPECT_FALSE(separateEnvironmentSun(makeEnvironmentMap(w, h, t)).has_value()) << "a small highlight";
  EXPECT_FALSE(separateEnvironmentSun(makeEnvironmentMap(w, h, std::vector<glm::vec3>(size_t(w) * h, glm::vec3(0.0f)))))
      << "a black map";
}

TEST(EnvironmentMap, TexelSolidAnglesCoverTheSphere) {
  const EnvironmentMap m = uniform(64, 32, glm::vec3(1.0f));
  double sum = 0.0;
  for (uint32_t r = 0; r < m.height; ++r) sum += environmentTexelSolidAngle(m, r) * m.width;
  EXPECT_NEAR(sum, 4.0 * M_PI, 1e-9);
}

TEST(EnvironmentMap, UniformMapIsTheUniformSky) {
  // Plane under a uniform sky: E = pi L for every normal; the band-limited radiance is L.
  const glm::vec3 l(0.5f, 1.0f, 2.0f);
  const EnvironmentMap m = uniform(64, 32, l);
  const auto sh = environmentSh9(m, 0.7f, 3.0f);
  glm::vec4 coefficients[9];
  for (int i = 0; i < 9; ++i) coefficients[i] = sh[size_t(i)];
  for (const glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, 2, -3))}) {
    const glm::vec3 e = shared::tlEnvShIrradiance(coefficients, n);
    // Band 2 integrates to 0 only up to the texel quadrature (each row's sin^2 at its centre):
    // 5e-4 measured at 32 rows; a missing band weight or solid angle is off by far more.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], float(M_PI) * 3.0f * l[k], 1.5e-3f * 3.0f * l[k] * float(M_PI));
    const glm::vec3 r = shared::tlEnvShRadiance(coefficients, n);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r[k], 3.0f * l[k], 3e-3f * 3.0f * l[k]);
  }
}

TEST(EnvironmentMap, SkyAboveTheHorizonGivesTheHemisphereIrradiance) {
  // Radiance 1 above the horizon, 0 below: E(up) = pi, E(sideways) = pi/2, E(down) = 0. For this
  // step the order-2 projection is exact at these three normals (band 2 vanishes by symmetry),
  // so only the texel quadrature is left.
  const uint32_t w = 128, h = 64;
  std::vector<glm::vec3> t(size_t(w) * h);
  for (uint32_t r = 0; r < h; ++r)
    for (uint32_t c = 0; c < w; ++c) t[size_t(r) * w + c] = glm::vec3(r < h / 2 ? 1.0f : 0.0f);
  const auto sh = environmentSh9(makeEnvironmentMap(w, h, t), 0.0f, 1.0f);
  glm::vec4 coefficients[9];
  for (int i = 0; i < 9; ++i) coefficients[i] = sh[size_t(i)];
  EXPECT_NEAR(shared::tlEnvShIrradiance(coefficients, glm::vec3(0, 1, 0)).x, float(M_PI), 2e-3f);
  EXPECT_NEAR(shared::tlEnvShIrradiance(coefficients, glm::vec3(1, 0, 0)).x, 0.5f * float(M_PI), 2e-3f);
  EXPECT_NEAR(shared::tlEnvShIrradiance(coefficients, glm::vec3(0, -1, 0)).x, 0.0f, 2e-3f);
}

// The table's density for a texel, as common/environment.glsl computes it (at the texel centre).
double tableDensity(const std::vector<float>& table, const EnvironmentMap& m, uint32_t c, uint32_t r) {
  const uint32_t mo = shared::tlEnvMarginalOffset(m.width, m.height), co = shared::tlEnvConditionalOffset(m.width, m.height, r);
  const double p = double(table[mo + r + 1] - table[mo + r]) * double(table[co + c + 1] - table[co + c]);
  return p * m.width * m.height / (2.0 * M_PI * M_PI * std::sin(M_PI * (r + 0.5) / m.height));
}

TEST(EnvironmentMap, TableIsADensityProportionalToRadiance) {
  // Any map: the density integrates to 1 over the sphere and is proportional to luminance, so
  // L / pdf is the same for every texel that has light (zero variance for a one-colour sky).
  const uint32_t w = 32, h = 16;
  std::vector<glm::vec3> t(size_t(w) * h);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (auto& x : t) x = glm::vec3(u(rng));
  t[5] = glm::vec3(0.0f);
  const EnvironmentMap m = makeEnvironmentMap(w, h, t);
  const auto table = environmentTable(m);
  ASSERT_EQ(table.size(), size_t(shared::tlEnvTableFloats(w, h)));
  double integral = 0.0, lOverPdf = -1.0;
  for (uint32_t r = 0; r < h; ++r)
    for (uint32_t c = 0; c < w; ++c) {
      const double pdf = tableDensity(table, m, c, r);
      integral += pdf * environmentTexelSolidAngle(m, r);
      const double l = t[size_t(r) * w + c].x;
      if (l == 0.0) {
        EXPECT_EQ(pdf, 0.0);
        continue;
      }
      if (lOverPdf < 0.0) lOverPdf = l / pdf;
      // sin(theta) at the centre against the texel's exact solid angle: within 0.5% at 16 rows.
      EXPECT_NEAR(l / pdf / lOverPdf, 1.0, 5e-3) << c << "," << r;
    }
  EXPECT_NEAR(integral, 1.0, 5e-3);
  // A uniform sky is sampled uniformly over the sphere: pdf = 1 / (4 pi) everywhere.
  const EnvironmentMap flat = uniform(w, h, glm::vec3(2.0f));
  const auto ft = environmentTable(flat);
  for (uint32_t r = 0; r < h; r += 5) EXPECT_NEAR(tableDensity(ft, flat, 3, r) * 4.0 * M_PI, 1.0, 5e-3);
}

TEST(EnvironmentMap, OneBrightTexelIsADirectionalLight) {
  // All the table's weight in one texel: every sample lands in it, and the estimate
  // L cos / pdf of a surface facing it is L x (the texel's solid angle) = E of a directional light.
  const uint32_t w = 64, h = 32, c = 40, r = 9;
  std::vector<glm::vec3> t(size_t(w) * h, glm::vec3(0.0f));
  t[size_t(r) * w + c] = glm::vec3(1000.0f);
  const EnvironmentMap m = makeEnvironmentMap(w, h, t);
  const auto table = environmentTable(m);
  const double omega = environmentTexelSolidAngle(m, r);
  EXPECT_NEAR(tableDensity(table, m, c, r) * omega, 1.0, 5e-3);
  const uint32_t mo = shared::tlEnvMarginalOffset(w, h);
  EXPECT_EQ(table[mo + r], 0.0f);
  EXPECT_EQ(table[mo + r + 1], 1.0f);
}

TEST(EnvironmentMap, ReadFromAnExrAtFullFloatPrecision) {
  TempDir tmp;
  const fs::path file = tmp.path / "sky.exr";
  std::vector<float> values = {1.0f, 2.0f, 3.0f, 1e6f, 0.5f, 0.25f, 0.0f, 0.0f, 0.0f, 4.0f, 4.0f, 4.0f};
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out && out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close());
  const EnvironmentMap m = loadEnvironmentMap(file);
  EXPECT_EQ(m.width, 2u);
  EXPECT_EQ(m.height, 2u);
  EXPECT_EQ(m.radiance[1], glm::vec3(1e6f, 0.5f, 0.25f));  // a sun above half floats' 65504 keeps its value
  EXPECT_NE(m.contentHash, 0u);
}

TEST(EnvironmentMap, UnusableFilesAreOneClearError) {
  TempDir tmp;
  auto errorOf = [](const fs::path& f) -> std::string {
    try {
      loadEnvironmentMap(f);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(errorOf(tmp.path / "missing.exr").find("missing.exr"), std::string::npos);
  const fs::path text = tmp.path / "notes.hdr";
  std::ofstream(text) << "not an image";
  EXPECT_NE(errorOf(text).find("environment map"), std::string::npos);
  const fs::path negative = tmp.path / "negative.exr";
  std::vector<float> values = {1.0f, -2.0f, 3.0f, 1.0f, 1.0f, 1.0f};
  auto out = OIIO::ImageOutput::create(negative.string());
  OIIO::ImageSpec spec(2, 1, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out && out->open(negative.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close());
  EXPECT_NE(errorOf(negative).find("texel (0, 0) has radiance -2"), std::string::npos);
}

}  // namespace
}  // namespace tl::scene
