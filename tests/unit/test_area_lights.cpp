// Area lights (shaders/shared/area_lights.h) against closed forms, on the CPU:
//   - the irradiance on the axis of a one-sided disk of radiance L, radius r, height h:
//     E = pi L r^2 / (r^2 + h^2), and off the axis the form factor of a point to a parallel disk;
//   - a parallel rectangle's form factor (the corner formula, summed with signs) anywhere under it;
//   - a one-sided light sends nothing behind it, a two-sided one the same to both sides;
//   - sampling a point on the shape is an unbiased estimate of the same irradiance (a tube's
//     ribbon included, whose far field is the cylinder's: L 2 r length / d^2), and a ray's hit
//     has the pdf the sample had;
//   - the table's shape, units and power (pi L A).
#include "lighting/common/light_table.h"
#include "shared/lights.h"
#include "shared/shading.h"
#include "shared/area_specular.h"

#include <gtest/gtest.h>

#include "../common/form_factors.h"

#include <cmath>

namespace tl::lighting {
namespace {

using shared::GpuLight;
using shared::LightIncidence;

constexpr double kPi = 3.14159265358979323846;

// A light facing down (-y) at height h over the origin, radiance L = 1 (683 nits).
scene::Light areaLight(scene::LightType type, double h) {
  scene::Light l;
  l.type = type;
  l.intensity = 683.0f;
  l.position = {0.0, h, 0.0};
  l.direction = {0.0, -1.0, 0.0};
  return l;
}

GpuLight tableOf(const scene::Light& l) {
  const auto table = buildLightTable({l}, glm::dvec3(0.0), 10.0);
  EXPECT_EQ(table.size(), 1u);
  return table.at(0);
}

// Irradiance on a surface of normal n at p from the analytic term, as every path applies it
// (irradiance times the clamped cosine).
double analyticIrradiance(const GpuLight& g, glm::vec3 p, glm::vec3 n = {0, 1, 0}) {
  const LightIncidence li = shared::tlLightIncidence(g, p);
  return double(li.irradiance.x) * std::max(double(glm::dot(n, li.toLight)), 0.0);
}

// The mean of `count` one-point estimates on a stratified grid (the next-event estimate).
double sampledIrradiance(const GpuLight& g, glm::vec3 p, glm::vec3 n = {0, 1, 0}, int side = 256) {
  double sum = 0.0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const glm::vec2 u((float(i) + 0.5f) / float(side), (float(j) + 0.5f) / float(side));
      const LightIncidence li = shared::tlAreaLightSample(g, p, u);
      sum += double(li.irradiance.x) * std::max(double(glm::dot(n, li.toLight)), 0.0);
    }
  return sum / double(side * side);
}

using test::cornerFormFactor;
using test::diskFormFactor;
using test::rectFormFactor;

TEST(AreaLights, DiskOnItsAxisGivesPiLRSquaredOverRSquaredPlusHSquared) {
  for (double h : {0.1, 0.5, 1.0, 2.0, 10.0}) {
    scene::Light disk = areaLight(scene::LightType::Disk, h);
    disk.radius = 0.5f;
    const GpuLight g = tableOf(disk);
    const double exact = kPi * 0.25 / (0.25 + h * h);
    EXPECT_NEAR(analyticIrradiance(g, {0, 0, 0}) / exact, 1.0, 1e-3) << "h = " << h;
    EXPECT_NEAR(sampledIrradiance(g, {0, 0, 0}) / exact, 1.0, 2e-3) << "h = " << h;
  }
}

TEST(AreaLights, DiskOffItsAxisFollowsThePointToDiskFormFactor) {
  scene::Light disk = areaLight(scene::LightType::Disk, 1.0);
  disk.radius = 0.5f;
  const GpuLight g = tableOf(disk);
  for (double a : {0.25, 0.49, 0.8, 2.0}) {
    const double exact = kPi * diskFormFactor(0.5, 1.0, a);
    std::printf("disk a = %.2f: analytic %.6f sampled %.6f exact %.6f\n", a, analyticIrradiance(g, {float(a), 0, 0}),
                sampledIrradiance(g, {float(a), 0, 0}), exact);
    EXPECT_NEAR(analyticIrradiance(g, {float(a), 0, 0}) / exact, 1.0, 3e-3) << "a = " << a;
    EXPECT_NEAR(sampledIrradiance(g, {float(a), 0, 0}) / exact, 1.0, 3e-3) << "a = " << a;
  }
}

TEST(AreaLights, RectangleFollowsTheParallelRectangleFormFactorUnderAndBesideIt) {
  // 1.2 m (x) by 0.6 m (z), 1 m up.
  scene::Light rect = areaLight(scene::LightType::Rect, 1.0);
  rect.width = 1.2f;
  rect.height = 0.6f;
  const GpuLight g = tableOf(rect);
  for (double x : {0.0, 0.3, 0.6, 1.5}) {
    for (double z : {0.0, 0.2, -0.7}) {
      const double exact = kPi * rectFormFactor(-0.6 - x, 0.6 - x, -0.3 - z, 0.3 - z, 1.0);
      const glm::vec3 p(float(x), 0.0f, float(z));
      EXPECT_NEAR(analyticIrradiance(g, p) / exact, 1.0, 1e-4) << x << ", " << z;
      EXPECT_NEAR(sampledIrradiance(g, p) / exact, 1.0, 2e-3) << x << ", " << z;
    }
  }
}

TEST(AreaLights, ATiltedSurfaceGetsTheDotProductOfTheVectorIrradiance) {
  // A surface tilted 30 degrees whose horizon stays clear of the rectangle: the analytic term
  // is exact for it too (next-event estimation is the check).
  scene::Light rect = areaLight(scene::LightType::Rect, 1.0);
  rect.width = 0.5f;
  rect.height = 0.5f;
  const GpuLight g = tableOf(rect);
  const glm::vec3 n = glm::normalize(glm::vec3(0.5f, 0.866f, 0.0f)), p(0.1f, 0.0f, 0.2f);
  EXPECT_NEAR(analyticIrradiance(g, p, n) / sampledIrradiance(g, p, n), 1.0, 2e-3);
}

TEST(AreaLights, OneSidedLightsAreDarkBehindTwoSidedOnesAreSymmetric) {
  scene::Light rect = areaLight(scene::LightType::Rect, 1.0);
  const glm::vec3 above(0.0f, 2.0f, 0.0f), down(0.0f, -1.0f, 0.0f);
  EXPECT_EQ(analyticIrradiance(tableOf(rect), above, down), 0.0);
  EXPECT_EQ(sampledIrradiance(tableOf(rect), above, down, 8), 0.0);
  rect.twoSided = true;
  const GpuLight g = tableOf(rect);
  EXPECT_NEAR(analyticIrradiance(g, above, down), analyticIrradiance(g, {0, 0, 0}), 1e-6);
  EXPECT_GT(analyticIrradiance(g, above, down), 0.1);
}

TEST(AreaLights, TubeSendsWhatItsCylinderSendsAndSamplingAgrees) {
  // A tube along x, 2 m long, radius 5 cm, 1 m over the origin: the analytic ribbon and its
  // samples agree; from far away on its perpendicular bisector E = L 2 r length / d^2.
  scene::Light tube = areaLight(scene::LightType::Tube, 1.0);
  tube.direction = {1.0, 0.0, 0.0};
  tube.length = 2.0f;
  tube.radius = 0.05f;
  const GpuLight g = tableOf(tube);
  for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.7f, 0.0f, 0.4f), glm::vec3(2.5f, 0.0f, 0.0f)})
    EXPECT_NEAR(analyticIrradiance(g, p) / sampledIrradiance(g, p), 1.0, 3e-3) << p.x << ", " << p.z;
  const double d = 100.0;
  const glm::vec3 far(0.0f, float(1.0 - d), 0.0f);
  EXPECT_NEAR(analyticIrradiance(g, far) / (2.0 * 0.05 * 2.0 / (d * d)), 1.0, 1e-3);
  // On the axis's line the ribbon has no area: nothing, no NaN.
  EXPECT_EQ(analyticIrradiance(g, {3.0f, 1.0f, 0.0f}, {-1, 0, 0}), 0.0);
}

TEST(AreaLights, ARayMeetsTheShapeWhereASampleLiesWithTheSamplesPdf) {
  for (auto type : {scene::LightType::Rect, scene::LightType::Disk, scene::LightType::Tube}) {
    scene::Light l = areaLight(type, 1.5);
    if (type == scene::LightType::Tube) l.direction = {0.0, 0.0, 1.0};
    const GpuLight g = tableOf(l);
    const glm::vec3 p(0.3f, 0.0f, -0.2f);
    for (glm::vec2 u : {glm::vec2(0.1f, 0.2f), glm::vec2(0.5f, 0.5f), glm::vec2(0.9f, 0.35f)}) {
      const LightIncidence li = shared::tlAreaLightSample(g, p, u);
      ASSERT_GT(li.pdf, 0.0f);
      const shared::AreaHit h = shared::tlAreaLightHit(g, p, li.toLight);
      EXPECT_NEAR(h.t, li.distance, 1e-4 * li.distance) << int(type);
      EXPECT_NEAR(h.pdf / li.pdf, 1.0, 1e-4) << int(type);
    }
    // Away from the light: no hit.
    EXPECT_LT(shared::tlAreaLightHit(g, p, glm::vec3(0.0f, -1.0f, 0.0f)).t, 0.0f);
  }
  // A one-sided light is not met from behind.
  const GpuLight rect = tableOf(areaLight(scene::LightType::Rect, 1.0));
  EXPECT_LT(shared::tlAreaLightHit(rect, {0.0f, 2.0f, 0.0f}, {0.0f, -1.0f, 0.0f}).t, 0.0f);
}

TEST(AreaLights, TheTableHoldsTheShapeInRadianceUnitsAndDrawsByPower) {
  scene::Light rect = areaLight(scene::LightType::Rect, 2.0);
  rect.width = 2.0f;
  rect.height = 0.5f;
  rect.widthAxis = {0.0, 0.0, 3.0};
  scene::Light disk = areaLight(scene::LightType::Disk, 2.0);
  disk.radius = 0.5f;
  disk.twoSided = true;
  const auto table = buildLightTable({rect, disk}, glm::dvec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(table[0].type, shared::kLightRect);
  EXPECT_NEAR(table[0].intensity.x, 1.0f, 1e-6f);  // 683 nits: L = 1
  EXPECT_NEAR(table[0].position.x, -1.0f, 1e-6f);  // camera-relative
  EXPECT_NEAR(table[0].axisU.z, 1.0f, 1e-6f);      // half the width, along width_axis
  EXPECT_NEAR(glm::length(glm::vec3(table[0].axisV)), 0.25f, 1e-6f);
  EXPECT_EQ(table[1].axisV.w, 1.0f);
  // Power pi L A: 1 m^2 one side against 2 x pi/4 m^2.
  const double rectPower = kPi * 1.0, diskPower = kPi * 2.0 * kPi * 0.25;
  EXPECT_NEAR(table[0].intensity.w, rectPower / (rectPower + diskPower), 1e-6);
}

// The rasterising paths' glossy reflection of an area light (shared/area_specular.h: one point of
// the shape and one direction of the lobe, weighted by the power heuristic) against the integral
// over the shape (256 x 256 points of it). A gold-like metal (specular only) under a 1 x 1 m panel
// 2 m up and 2 m across, seen from (-2, 2, 0): at the highlight's centre (p = 0, the mirror
// direction through the panel's centre) and beside it (p = 0.5 m, 1 m: the mirror ray passes the
// panel's edge, then misses it). The estimate averaged over 4096 draws must be the integral (it
// is unbiased) within 2%, and one draw's spread stays moderate (the lobe's own samples find a
// narrow lobe's light). The old term (the lobe in the vector irradiance's direction, as for a
// point light of the panel's power) is printed beside it: 14.4x at roughness 0.15 and 2.34x at
// 0.3 at the centre, which is what the estimate replaces.
// The radiance a surface reflects from an area light (red), integrated over 256 x 256 points of
// the shape.
double reflectedOverShape(const GpuLight& g, const shared::SurfaceParams& s, glm::vec3 n, glm::vec3 v, glm::vec3 p) {
  double sum = 0.0;
  const int side = 256;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const LightIncidence si = shared::tlAreaLightSample(g, p, glm::vec2((float(i) + 0.5f) / float(side), (float(j) + 0.5f) / float(side)));
      sum += double(si.irradiance.x * shared::tlBrdf(s, n, v, si.toLight).x * std::max(glm::dot(n, si.toLight), 0.0f));
    }
  return sum / double(side * side);
}

TEST(AreaLights, TheGlossyReflectionOfAPanelIsTheIntegralOverIt) {
  scene::Light rect = areaLight(scene::LightType::Rect, 2.0);
  rect.position = {2.0, 2.0, 0.0};  // the mirror direction of a view from (-2, 2, 0)
  const GpuLight g = tableOf(rect);
  const glm::vec3 n(0, 1, 0), eye(-2.0f, 2.0f, 0.0f);
  for (float x : {0.0f, 0.5f, 1.0f}) {
    const glm::vec3 p(x, 0.0f, 0.0f), v = glm::normalize(eye - p);
    for (float roughness : {0.15f, 0.3f, 0.6f, 1.0f}) {
      const shared::SurfaceParams s = shared::tlMaterialSurface(glm::vec3(1.0f, 0.8f, 0.4f), roughness, 1.0f, shared::kMaterialsAuthored);
      const LightIncidence li = shared::tlLightIncidence(g, p);
      const double old = double(li.irradiance.x * shared::tlBrdf(s, n, v, li.toLight).x * std::max(glm::dot(n, li.toLight), 0.0f));
      const double exact = reflectedOverShape(g, s, n, v, p);
      double mean = 0.0, square = 0.0;
      const int draws = 4096;
      for (int k = 0; k < draws; ++k) {
        const glm::uvec3 seed(uint32_t(k), uint32_t(x * 10.0f), uint32_t(roughness * 100.0f));
        const double e = shared::tlAreaLightSpecular(g, s, n, v, p, shared::tlRandom2(seed), shared::tlRandom2(shared::tlPcg3d(seed))).x;
        mean += e / draws;
        square += e * e / draws;
      }
      const double spread = std::sqrt(std::max(square - mean * mean, 0.0)) / exact;
      std::printf("p = %.1f m, roughness %.2f: integral %.5f, estimate %.5f (ratio %.4f, one draw's spread %.2f), representative direction %.5f (%.3f)\n",
                  x, roughness, exact, mean, mean / exact, spread, old, old / exact);
      EXPECT_NEAR(mean / exact, 1.0, 3.0 * spread / std::sqrt(double(draws)) + 0.005) << x << " m, roughness " << roughness;
      EXPECT_LT(spread, 3.0) << x << " m, roughness " << roughness;
    }
  }
}

TEST(AreaLights, APanelThatFillsTheLobeIsReflectedAsTheRadianceTimesTheAlbedo) {
  // A 40 x 40 m panel 0.3 m above: the lobe sees nothing else, so the reflection is L rho_s(n.v)
  // (the environment's specular under uniform radiance L). The vector irradiance points straight
  // up while the mirror direction is 45 degrees off: the old term gave 3% of it.
  scene::Light rect = areaLight(scene::LightType::Rect, 0.3);
  rect.width = 40.0f;
  rect.height = 40.0f;
  const GpuLight g = tableOf(rect);
  const glm::vec3 n(0, 1, 0), p(0.0f), v = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.0f));
  const shared::SurfaceParams s = shared::tlMaterialSurface(glm::vec3(1.0f), 0.2f, 1.0f, shared::kMaterialsAuthored);
  const double want = double(g.intensity.x * shared::tlEnvironmentSpecular(s, glm::dot(n, v)).x);
  double mean = 0.0;
  const int draws = 4096;
  for (int k = 0; k < draws; ++k) {
    const glm::uvec3 seed(uint32_t(k), 7u, 11u);
    mean += shared::tlAreaLightSpecular(g, s, n, v, p, shared::tlRandom2(seed), shared::tlRandom2(shared::tlPcg3d(seed))).x / draws;
  }
  const LightIncidence li = shared::tlLightIncidence(g, p);
  const double old = double(li.irradiance.x * shared::tlBrdf(s, n, v, li.toLight).x * glm::dot(n, li.toLight));
  std::printf("estimate %.5f, L rho_s %.5f, old term %.5f\n", mean, want, old);
  EXPECT_NEAR(mean / want, 1.0, 0.02);
}

// What a still image shows after k frames: the mean of k estimates per pixel. lights.direct walks
// an R2 sequence from a random shift per pixel (common/lights.glsl areaGlossyDraws); against
// independent draws its error after 16 frames, as an RMS over 1024 pixels' shifts of the
// relative error of their means, on the panel's highlight and beside it at roughness 0.3 and 0.6.
// Both are unbiased (their means over the pixels match the integral); the sequence's error must
// be below the independent draws' (measured 0.45-0.67 of it: the shape's edge makes the
// integrand discontinuous, which the sequence does not stratify as well as a smooth one).
TEST(AreaLights, TheGlossyEstimateConvergesFasterOverFramesOnTheR2Sequence) {
  scene::Light rect = areaLight(scene::LightType::Rect, 2.0);
  rect.position = {2.0, 2.0, 0.0};
  const GpuLight g = tableOf(rect);
  const glm::vec3 n(0, 1, 0), eye(-2.0f, 2.0f, 0.0f);
  const uint32_t frames = 16, pixels = 1024;
  for (float x : {0.0f, 0.5f}) {
    for (float roughness : {0.3f, 0.6f}) {
      const glm::vec3 p(x, 0.0f, 0.0f), v = glm::normalize(eye - p);
      const shared::SurfaceParams s = shared::tlMaterialSurface(glm::vec3(1.0f, 0.8f, 0.4f), roughness, 1.0f, shared::kMaterialsAuthored);
      const double exact = reflectedOverShape(g, s, n, v, p);
      double squareR2 = 0.0, squareIndependent = 0.0, meanR2 = 0.0;
      for (uint32_t pixel = 0; pixel < pixels; ++pixel) {
        const glm::uvec3 h = shared::tlPcg3d(glm::uvec3(pixel, 17u, 3u)), h2 = shared::tlPcg3d(h);
        double r2 = 0.0, independent = 0.0;
        for (uint32_t k = 0; k < frames; ++k) {
          r2 += shared::tlAreaLightSpecular(g, s, n, v, p, shared::tlR2Point(k, glm::uvec2(h.x, h.y)), shared::tlR2Point(k, glm::uvec2(h2.x, h2.y))).x;
          const glm::uvec3 seed(pixel, k, 5u);
          independent += shared::tlAreaLightSpecular(g, s, n, v, p, shared::tlRandom2(seed), shared::tlRandom2(shared::tlPcg3d(seed))).x;
        }
        r2 /= frames, independent /= frames;
        meanR2 += r2 / pixels;
        squareR2 += (r2 / exact - 1.0) * (r2 / exact - 1.0) / pixels;
        squareIndependent += (independent / exact - 1.0) * (independent / exact - 1.0) / pixels;
      }
      const double rmsR2 = std::sqrt(squareR2), rmsIndependent = std::sqrt(squareIndependent);
      std::printf("p = %.1f m, roughness %.1f, %u frames: RMS error R2 %.4f, independent %.4f (%.2fx); R2 mean over pixels %.4f of the integral\n",
                  x, roughness, frames, rmsR2, rmsIndependent, rmsIndependent / rmsR2, meanR2 / exact);
      EXPECT_NEAR(meanR2 / exact, 1.0, 0.02) << x << " m, roughness " << roughness;
      EXPECT_LT(rmsR2, 0.8 * rmsIndependent) << x << " m, roughness " << roughness;
    }
  }
}

}  // namespace
}  // namespace tl::lighting
