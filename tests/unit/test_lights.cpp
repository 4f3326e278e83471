// The light table and the shared light math (shaders/shared/lights.h) against closed forms:
// a point light's irradiance on a plane E = I cos(theta) / d^2, KHR_lights_punctual's cone
// falloff and range window, and the table's units, positions and selection probabilities.
#include "lighting/common/light_table.h"
#include "shared/lights.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tl::lighting {
namespace {

using shared::GpuLight;
using shared::LightIncidence;

scene::Light pointLight(glm::dvec3 position, float candela) {
  scene::Light l;
  l.type = scene::LightType::Point;
  l.intensity = candela;
  l.position = position;
  return l;
}

TEST(Lights, PointLightOverAPlaneFollowsTheInverseSquareAndCosineLaw) {
  // I = 683 cd is I = 1 on Twinlight's scale; 2 m above the plane's origin, seen from (x, 0, 0).
  const auto table = buildLightTable({pointLight({0.0, 2.0, 0.0}, 683.0f)}, glm::dvec3(0.0), 10.0);
  ASSERT_EQ(table.size(), 1u);
  for (double x : {0.0, 0.5, 1.0, 3.0}) {
    const LightIncidence li = shared::tlLightIncidence(table[0], glm::vec3(float(x), 0.0f, 0.0f));
    const double d2 = 4.0 + x * x, cosTheta = 2.0 / std::sqrt(d2);
    const double irradiance = double(li.irradiance.x) * double(glm::dot(glm::vec3(0, 1, 0), li.toLight));
    EXPECT_NEAR(irradiance, cosTheta / d2, 1e-6 * cosTheta / d2) << "x = " << x;
    EXPECT_NEAR(li.distance, std::sqrt(d2), 1e-6);
  }
}

TEST(Lights, TheTableIsCameraRelativeAndDrawsEachLightInProportionToItsPower) {
  scene::Light spot = pointLight({10.0, 5.0, 0.0}, 683.0f);
  spot.type = scene::LightType::Spot;
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.5f;
  spot.direction = {0.0, -1.0, 0.0};
  scene::Light dark = pointLight({0.0, 0.0, 0.0}, 0.0f);
  const glm::dvec3 camera(1000.0, 0.0, -2000.0);
  const auto table = buildLightTable({pointLight({1001.0, 2.0, -2000.0}, 3.0f * 683.0f), dark, spot}, camera, 10.0);
  ASSERT_EQ(table.size(), 2u) << "a light that emits nothing is left out";
  EXPECT_EQ(glm::vec3(table[0].position), glm::vec3(1.0f, 2.0f, 0.0f));
  EXPECT_EQ(table[0].type, shared::kLightPoint);
  EXPECT_EQ(table[1].type, shared::kLightSpot);
  EXPECT_NEAR(table[1].cosOuter, std::cos(0.5f), 1e-7f);
  // Power: 4 pi * 3 against 2 pi (1 - cos 0.5) * 1.
  const double point = 4.0 * M_PI * 3.0, cone = 2.0 * M_PI * (1.0 - std::cos(0.5));
  EXPECT_NEAR(table[0].intensity.w, point / (point + cone), 1e-6);
  EXPECT_NEAR(table[1].intensity.w, cone / (point + cone), 1e-6);
  EXPECT_NEAR(table[0].direction.w, table[0].intensity.w, 1e-7);
  EXPECT_EQ(table[1].direction.w, 1.0f);
  EXPECT_TRUE(buildLightTable({}, camera, 10.0).empty());
  // A light the artist hid is left out as if it were not there: the others' shares are as before.
  scene::Light hidden = pointLight({1000.0, 9.0, -2000.0}, 50.0f * 683.0f);
  hidden.hidden = true;
  const auto withHidden = buildLightTable({pointLight({1001.0, 2.0, -2000.0}, 3.0f * 683.0f), hidden, dark, spot}, camera, 10.0);
  ASSERT_EQ(withHidden.size(), 2u);
  EXPECT_EQ(withHidden[0].intensity.w, table[0].intensity.w);
  EXPECT_EQ(withHidden[1].type, shared::kLightSpot);
}

TEST(Lights, SpotConeFalloffAndRangeWindowFollowKhrLightsPunctual) {
  scene::Light spot = pointLight({0.0, 1.0, 0.0}, 683.0f);
  spot.type = scene::LightType::Spot;
  spot.innerConeAngle = 0.2f;
  spot.outerConeAngle = 0.6f;
  spot.direction = {0.0, -1.0, 0.0};
  const GpuLight g = buildLightTable({spot}, glm::dvec3(0.0), 10.0)[0];
  const double cosInner = std::cos(0.2), cosOuter = std::cos(0.6);
  // A point on the plane y = 0 at angle a off the axis: E = I cos(a) / d^2 times the falloff,
  // the square of (cos a - cos outer) / (cos inner - cos outer), clamped to [0, 1].
  for (double a : {0.0, 0.1, 0.3, 0.4, 0.5, 0.59, 0.7}) {
    const glm::vec3 p(float(std::tan(a)), 0.0f, 0.0f);
    const LightIncidence li = shared::tlLightIncidence(g, p);
    const double d2 = 1.0 + std::tan(a) * std::tan(a);
    const double t = std::clamp((std::cos(a) - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    const double expected = t * t / d2;
    EXPECT_NEAR(li.irradiance.x, expected, 1e-5 * std::max(expected, 1e-3)) << "angle " << a;
  }
  EXPECT_EQ(shared::tlLightIncidence(g, glm::vec3(0.0f, 2.0f, 0.0f)).irradiance.x, 0.0f) << "behind the spot";
  // Range 4 m: the inverse square law times max(1 - (d / 4)^4, 0).
  scene::Light ranged = pointLight({0.0, 0.0, 0.0}, 683.0f);
  ranged.range = 4.0f;
  const GpuLight r = buildLightTable({ranged}, glm::dvec3(0.0), 10.0)[0];
  for (double d : {1.0, 2.0, 3.5, 4.0, 5.0}) {
    const double expected = std::max(1.0 - std::pow(d / 4.0, 4.0), 0.0) / (d * d);
    EXPECT_NEAR(shared::tlLightIncidence(r, glm::vec3(float(d), 0.0f, 0.0f)).irradiance.x, expected, 1e-6) << d;
  }
}

TEST(Lights, DirectionalLightsGiveTheirIrradianceFromTheirDirection) {
  scene::Light fill;
  fill.type = scene::LightType::Directional;
  fill.intensity = 683.0f * 2.0f;
  fill.color = {1.0f, 0.5f, 0.0f};
  fill.direction = glm::normalize(glm::dvec3(1.0, -1.0, 0.0));
  const GpuLight g = buildLightTable({fill}, glm::dvec3(5.0), 10.0)[0];
  const LightIncidence li = shared::tlLightIncidence(g, glm::vec3(123.0f, -4.0f, 9.0f));
  EXPECT_NEAR(li.irradiance.x, 2.0f, 1e-6f);
  EXPECT_NEAR(li.irradiance.y, 1.0f, 1e-6f);
  EXPECT_NEAR(li.toLight.x, -std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(li.toLight.y, std::sqrt(0.5f), 1e-6f);
}

}  // namespace
}  // namespace tl::lighting
