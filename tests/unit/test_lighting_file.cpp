// The lighting sidecar (session/lighting_file.h) and colour temperature (scene/color_temperature.h):
// a file written and read back is the same lighting and the same text; every bad value is one
// error naming the key; black-body colours against the CIE's published chromaticities.
#include "../common/temp_dir.h"
#include "scene/color_temperature.h"
#include "session/lighting_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace tl::session {
namespace {

namespace fs = std::filesystem;

TEST(ColorTemperature, BlackBodiesLandOnThePublishedChromaticities) {
  // CIE standard illuminant A is a black body at 2856 K: x = 0.44757, y = 0.40745 (CIE 15:2004).
  const glm::dvec2 a = scene::blackBodyChromaticity(2856.0);
  EXPECT_NEAR(a.x, 0.44757, 0.002);
  EXPECT_NEAR(a.y, 0.40745, 0.002);
  // The Planckian locus at 6500 K: x = 0.3135, y = 0.3236 (near D65's 0.3127, 0.3290).
  const glm::dvec2 w = scene::blackBodyChromaticity(6500.0);
  EXPECT_NEAR(w.x, 0.3135, 0.002);
  EXPECT_NEAR(w.y, 0.3236, 0.002);
}

TEST(ColorTemperature, SixtyFiveHundredKelvinIsNearWhiteAndTheRgbHasLuminanceOne) {
  const glm::vec3 white = scene::colorTemperatureToRgb(6500.0);
  std::printf("6500 K: %.4f %.4f %.4f\n", white.r, white.g, white.b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], 1.0f, 0.06f) << c;
  for (double k : {1000.0, 1850.0, 2700.0, 4000.0, 6500.0, 10000.0, 40000.0}) {
    const glm::vec3 c = scene::colorTemperatureToRgb(k);
    EXPECT_NEAR(0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b, 1.0, 1e-5) << k;
    EXPECT_GE(std::min({c.r, c.g, c.b}), 0.0f) << k;
  }
  // Warm lamps are red over blue, a clear sky blue over red, and monotonically so.
  const glm::vec3 tungsten = scene::colorTemperatureToRgb(2700.0), sky = scene::colorTemperatureToRgb(15000.0);
  EXPECT_GT(tungsten.r, tungsten.g);
  EXPECT_GT(tungsten.g, tungsten.b);
  EXPECT_GT(sky.b, sky.r);
  double previous = 1e9;
  for (double k = 1500.0; k <= 20000.0; k += 500.0) {
    const glm::vec3 c = scene::colorTemperatureToRgb(k);
    EXPECT_LT(c.r / c.g, previous) << k;  // green never leaves the gamut; blue is 0 below ~1900 K
    previous = c.r / c.g;
  }
}

class LightingFileTest : public ::testing::Test {
 protected:
  test::TempDir scratch;
  const fs::path& dir = scratch.path;
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p;
  }
  // The error `text` gives when read (empty: none).
  std::string error(const std::string& text) {
    try {
      readLightingFile(write("bad.lighting.json", text), Lighting{});
    } catch (const SessionError& e) {
      return e.what();
    }
    return "";
  }
};

Lighting sample() {
  Lighting l;
  l.sunDirection = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
  l.sunIrradiance = {3.0f, 2.5f, 2.0f};
  l.sunAngularRadius = 0.01f;
  l.skyRadiance = {0.1f, 0.2f, 0.4f};
  l.exposureEv = -1.5f;
  scene::Light p;
  p.name = "bulb";
  p.type = scene::LightType::Point;
  p.position = {1.0, 2.5, -0.75};
  p.color = {1.0f, 0.8f, 0.6f};
  p.intensity = 683.0f;
  p.range = 8.0f;
  scene::Light s;
  s.name = "spot";
  s.type = scene::LightType::Spot;
  s.position = {0.0, 3.0, 0.0};
  s.direction = glm::normalize(glm::dvec3(0.1, -1.0, 0.0));
  s.innerConeAngle = 0.25f;
  s.outerConeAngle = 0.6f;
  s.intensity = 1200.0f;
  scene::Light d;
  d.type = scene::LightType::Directional;
  d.direction = {0.0, -1.0, 0.0};
  d.intensity = 5000.0f;
  scene::Light r;
  r.name = "panel";
  r.type = scene::LightType::Rect;
  r.position = {0.5, 2.9, 0.0};
  r.direction = {0.0, -1.0, 0.0};
  r.widthAxis = {0.0, 0.0, 1.0};
  r.width = 1.2f;
  r.height = 0.6f;
  r.intensity = 2000.0f;  // nits
  scene::Light c;
  c.name = "disk";
  c.type = scene::LightType::Disk;
  c.position = {-1.0, 2.9, 0.0};
  c.direction = {0.0, -1.0, 0.0};
  c.radius = 0.3f;
  c.twoSided = true;
  c.intensity = 1500.0f;
  scene::Light t;
  t.name = "tube";
  t.type = scene::LightType::Tube;
  t.position = {0.0, 2.5, 1.0};
  t.direction = {1.0, 0.0, 0.0};
  t.radius = 0.02f;
  t.length = 1.5f;
  t.intensity = 5000.0f;
  l.lights = {p, s, d, r, c, t};
  return l;
}

TEST_F(LightingFileTest, WrittenAndReadBackIsTheSameLightingAndTheSameText) {
  const Lighting l = sample();
  const fs::path file = dir / "scene.lighting.json";
  writeLightingFile(file, l);
  const Lighting back = readLightingFile(file, Lighting{});
  EXPECT_EQ(back.sunDirection, l.sunDirection);
  EXPECT_EQ(back.sunIrradiance, l.sunIrradiance);
  EXPECT_EQ(back.sunAngularRadius, l.sunAngularRadius);
  EXPECT_EQ(back.skyRadiance, l.skyRadiance);
  EXPECT_EQ(back.exposureEv, l.exposureEv);
  EXPECT_FALSE(back.environmentMap);
  ASSERT_EQ(back.lights.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(back.lights[i].name, l.lights[i].name);
    EXPECT_EQ(back.lights[i].type, l.lights[i].type);
    EXPECT_EQ(back.lights[i].color, l.lights[i].color);
    EXPECT_EQ(back.lights[i].intensity, l.lights[i].intensity);
    EXPECT_EQ(back.lights[i].range, l.lights[i].range);
    EXPECT_EQ(back.lights[i].innerConeAngle, l.lights[i].innerConeAngle);
    EXPECT_EQ(back.lights[i].outerConeAngle, l.lights[i].outerConeAngle);
    if (scene::isAreaLight(l.lights[i].type)) {
      EXPECT_EQ(back.lights[i].position, l.lights[i].position);
      EXPECT_EQ(back.lights[i].direction, l.lights[i].direction);
      EXPECT_EQ(back.lights[i].width, l.lights[i].width);
      EXPECT_EQ(back.lights[i].height, l.lights[i].height);
      EXPECT_EQ(back.lights[i].radius, l.lights[i].radius);
      EXPECT_EQ(back.lights[i].length, l.lights[i].length);
      EXPECT_EQ(back.lights[i].twoSided, l.lights[i].twoSided);
    }
  }
  EXPECT_EQ(back.lights[3].widthAxis, l.lights[3].widthAxis);
  EXPECT_EQ(back.lights[0].position, l.lights[0].position);
  EXPECT_EQ(back.lights[1].direction, l.lights[1].direction);
  EXPECT_EQ(lightingJson(back, dir), lightingJson(l, dir));
  EXPECT_EQ(lightingSidecarPath("a/b/scene.gltf"), fs::path("a/b/scene.lighting.json"));
}

TEST_F(LightingFileTest, WritingIntoAFolderThatDoesNotExistYetMakesIt) {
  // Like --out for images: --save-lighting into a new folder must not depend on something else
  // having made it first.
  const fs::path file = dir / "new" / "deeper" / "scene.lighting.json";
  writeLightingFile(file, sample());
  EXPECT_EQ(readLightingFile(file, Lighting{}).lights.size(), 6u);
  EXPECT_FALSE(fs::exists(fs::path(file) += ".tmp"));
}

TEST_F(LightingFileTest, AbsentKeysKeepTheBaseAndTemperaturesBecomeRgb) {
  const Lighting base = sample();
  const Lighting l = readLightingFile(write("t.lighting.json", R"({"format": "twinlight.lighting", "version": 1,
      "sky": {"temperature_k": 6500, "radiance": 2},
      "lights": [{"type": "point", "position": [0, 1, 0], "temperature_k": 2700, "intensity": 100}]})"),
                                      base);
  EXPECT_EQ(l.sunIrradiance, base.sunIrradiance);  // no "sun": kept
  EXPECT_EQ(l.exposureEv, base.exposureEv);
  ASSERT_EQ(l.lights.size(), 1u);
  const glm::vec3 warm = scene::colorTemperatureToRgb(2700.0);
  EXPECT_EQ(l.lights[0].color, warm);
  EXPECT_GT(warm.r, warm.b);
  const glm::vec3 sky = scene::colorTemperatureToRgb(6500.0) * 2.0f;
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(l.skyRadiance[c], sky[c]);
}

TEST_F(LightingFileTest, EveryBadValueIsOneErrorNamingItsKey) {
  const std::string head = R"({"format": "twinlight.lighting", "version": 1, )";
  const struct {
    std::string body, key;
  } cases[] = {
      {R"("sun": {"direction": [0, 0, 0], "irradiance": 1}})", "sun.direction"},
      {R"("sun": {"direction": [0, -1, 0], "irradiance": -1}})", "sun.irradiance"},
      {R"("sun": {"direction": [0, -1, 0]}})", "sun.irradiance"},
      {R"("sky": {"radiance": [1, 2]}})", "sky.radiance"},
      {R"("sky": {"radiance": 1, "temperature_k": 500}})", "sky.temperature_k"},
      {R"("sky": {"radiance": 1, "colour": [1, 1, 1]}})", "sky.colour"},
      {R"("exposure_ev": 100})", "exposure_ev"},
      {R"("environment": {"file": "missing.exr"}})", "environment.file"},
      {R"("environment": {"file": "missing.exr", "rotation_deg": 720}})", "environment.rotation_deg"},
      {R"("lights": [{"type": "area", "intensity": 1}]})", "lights[0].type"},
      {R"("lights": [{"type": "point", "intensity": 1}]})", "lights[0].position"},
      {R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1e11}]})", "lights[0].intensity"},
      {R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1e9, "color": [100, 1, 1]}]})", "lights[0].intensity"},
      {R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1, "color": [1, 1, 1], "temperature_k": 3000}]})", "lights[0]"},
      {R"("lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 1, "inner_cone_deg": 40, "outer_cone_deg": 30}]})", "lights[0]"},
      {R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1, "range": 0}]})", "lights[0].range"},
      {R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1, "direction": [0, 1, 0]}]})", "lights[0].direction"},
      {R"("lights": {}})", "lights"},
      // Area lights: every size more than 0 (also as a float), the shape's keys only, no range,
      // a width axis not along the normal.
      {R"("lights": [{"type": "rect", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "width": 1}]})", "lights[0].height"},
      {R"("lights": [{"type": "rect", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "width": -1, "height": 1}]})", "lights[0].width"},
      {R"("lights": [{"type": "disk", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "radius": 1e-300}]})", "lights[0].radius"},
      {R"("lights": [{"type": "disk", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "radius": 1, "width": 1}]})", "lights[0].width"},
      {R"("lights": [{"type": "disk", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "radius": 1, "range": 3}]})", "lights[0].range"},
      {R"("lights": [{"type": "disk", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "radius": 1, "two_sided": 1}]})", "lights[0].two_sided"},
      {R"("lights": [{"type": "rect", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 100, "width": 1, "height": 1, "width_axis": [0, 2, 0]}]})", "lights[0].width_axis"},
      {R"("lights": [{"type": "tube", "position": [0, 2, 0], "direction": [1, 0, 0], "intensity": 100, "radius": 0.1}]})", "lights[0].length"},
      {R"("lights": [{"type": "tube", "position": [0, 2, 0], "direction": [1, 0, 0], "intensity": 100, "radius": 0.1, "length": 1, "two_sided": true}]})", "lights[0].two_sided"},
      {R"("lights": [{"type": "rect", "direction": [0, -1, 0], "intensity": 100, "width": 1, "height": 1}]})", "lights[0].position"},
      {R"("lights": [{"type": "rect", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 1e11, "width": 1, "height": 1}]})", "lights[0].intensity"},
      {R"("lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1, "radius": 1}]})", "lights[0]"},
  };
  for (const auto& c : cases) {
    const std::string e = error(head + c.body);
    EXPECT_NE(e.find("bad.lighting.json: " + c.key), std::string::npos) << c.body << "\n -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_NE(error(R"({"version": 1})").find("format"), std::string::npos);
  EXPECT_NE(error(R"({"format": "twinlight.lighting", "version": 2})").find("version"), std::string::npos);
  EXPECT_NE(error("{not json").find("not JSON"), std::string::npos);
  EXPECT_NE(error("[]").find("expected a JSON object"), std::string::npos);
}

}  // namespace
}  // namespace tl::session
