// glTF import of every content scene and of broken files: one clear single-line error
// naming the file, or a warning and a placeholder for a missing texture; content hashes
// stable across loads and renames, sensitive to content.
#include "../common/temp_dir.h"
#include "scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace tl::scene {
namespace {

using tl::test::contentFile;
using tl::test::TempDir;

namespace fs = std::filesystem;



void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(std::ifstream(p)); }

const Material* findMaterial(const Scene& s, const std::string& name) {
  for (auto& m : s.materials)
    if (m.name == name) return &m;
  return nullptr;
}

void expectWellFormed(const Scene& s) {
  ASSERT_FALSE(s.instances.empty());
  ASSERT_FALSE(s.materials.empty());
  ASSERT_FALSE(s.cameras.empty()) << s.name << " needs a default camera";
  EXPECT_TRUE(s.bounds.valid());
  for (auto& m : s.meshes) {
    EXPECT_FALSE(m.indices.empty()) << m.name;
    for (auto& v : m.vertices) {
      ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.normal.x) && std::isfinite(v.tangent.x)) << m.name;
      EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-3f) << m.name;
      EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-3f) << m.name;
      EXPECT_EQ(std::abs(v.tangent.w), 1.0f);
    }
  }
  for (auto& i : s.instances) EXPECT_LT(i.mesh, s.meshes.size());
}

TEST(SceneImport, Atrium) {
  Scene s = loadGltf(contentFile("atrium.gltf"));
  expectWellFormed(s);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_TRUE(s.environment.sunFromFile);
  EXPECT_NEAR(s.environment.sunIrradiance.x, 20.0f, 1e-4f);
  EXPECT_LT(s.environment.sunDirection.y, 0.0);  // sunlight travels downwards
  EXPECT_NEAR(s.environment.skyRadiance.z, 1.0f, 1e-6f);
  const Material* gold = findMaterial(s, "polished_gold");
  ASSERT_NE(gold, nullptr);
  EXPECT_EQ(gold->metallic, 1.0f);
  const Material* checker = findMaterial(s, "checker_textured");
  ASSERT_NE(checker, nullptr);
  ASSERT_TRUE(checker->baseColorTexture);
  const Texture& t = s.textures[checker->baseColorTexture->texture];
  EXPECT_FALSE(t.placeholder);
  EXPECT_TRUE(t.srgb);
  EXPECT_EQ(t.width, 64u);
  bool sawRoom = false;
  for (auto& i : s.instances) sawRoom |= i.name == "room_ceiling";
  EXPECT_TRUE(sawRoom);
}

TEST(SceneImport, CornellHasColouredWallsAndAnEmitter) {
  Scene s = loadGltf(contentFile("cornell.gltf"));
  expectWellFormed(s);
  const Material* red = findMaterial(s, "cornell_red");
  ASSERT_NE(red, nullptr);
  EXPECT_GT(red->baseColorFactor.r, 4.0f * red->baseColorFactor.g);
  const Material* light = findMaterial(s, "ceiling_light");
  ASSERT_NE(light, nullptr);
  EXPECT_NEAR(light->emissiveStrength, 15.0f, 1e-4f);
  EXPECT_FALSE(s.environment.sunFromFile);
  EXPECT_EQ(s.environment.skyRadiance, glm::vec3(0.0f));
}

TEST(SceneImport, FurnaceAndPlaneAreUnderAUniformSky) {
  for (const char* name : {"furnace.gltf", "plane.gltf"}) {
    Scene s = loadGltf(contentFile(name));
    expectWellFormed(s);
    EXPECT_EQ(s.environment.skyRadiance, glm::vec3(1.0f)) << name;
    EXPECT_FALSE(s.environment.sunFromFile) << name;
  }
  Scene plane = loadGltf(contentFile("plane.gltf"));
  EXPECT_NEAR(plane.bounds.size().x, 100.0, 1e-6);
}

TEST(SceneHashes, StableAcrossLoadsAndRenames) {
  Scene a = loadGltf(contentFile("atrium.gltf"));
  Scene b = loadGltf(contentFile("atrium.gltf"));
  EXPECT_EQ(a.contentHash, b.contentHash);
  TempDir tmp;
  // Copy under other names: the .gltf renamed, the texture directory kept (its uri).
  fs::copy_file(contentFile("atrium.bin"), tmp.path / "atrium.bin");
  fs::create_directories(tmp.path / "textures");
  fs::copy_file(contentFile("textures/checker.png"), tmp.path / "textures" / "checker.png");
  fs::copy_file(contentFile("atrium.gltf"), tmp.path / "renamed_scene.gltf");
  Scene c = loadGltf(tmp.path / "renamed_scene.gltf");
  EXPECT_EQ(a.contentHash, c.contentHash);
  for (size_t i = 0; i < a.materials.size(); ++i) EXPECT_EQ(a.materials[i].contentHash, c.materials[i].contentHash);
}

TEST(SceneHashes, ChangeExactlyWithContent) {
  Scene base = loadGltf(contentFile("plane.gltf"));
  TempDir tmp;
  fs::copy_file(contentFile("plane.bin"), tmp.path / "plane.bin");
  auto j = readJson(contentFile("plane.gltf"));
  j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][0] = 0.5;
  writeText(tmp.path / "plane.gltf", j.dump());
  Scene changed = loadGltf(tmp.path / "plane.gltf");
  EXPECT_NE(changed.materials[0].contentHash, base.materials[0].contentHash);
  EXPECT_EQ(changed.meshes[0].contentHash, base.meshes[0].contentHash);  // geometry untouched
  EXPECT_NE(changed.contentHash, base.contentHash);
}

// ---- broken input ------------------------------------------------------------------------

std::string loadError(const fs::path& file) {
  try {
    loadGltf(file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

void expectOneLineErrorNaming(const fs::path& file, const std::string& what) {
  std::string e = loadError(file);
  EXPECT_NE(e.find(file.filename().string()), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_NE(e.find(what), std::string::npos) << e;
}

// A valid one-triangle glTF whose JSON the tests then break in one place each.
nlohmann::json triangle(const std::string& bin) {
  return {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", bin}, {"byteLength", 42}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
      {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
}

void writeTriangleBin(const fs::path& p, uint16_t lastIndex = 2, std::array<float, 9> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0}) {
  uint16_t idx[3] = {0, 1, lastIndex};
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(pos.data()), sizeof(float) * pos.size());
  f.write(reinterpret_cast<const char*>(idx), sizeof idx);
}

TEST(SceneErrors, ValidTriangleLoads) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  writeText(tmp.path / "ok.gltf", triangle("t.bin").dump());
  Scene s = loadGltf(tmp.path / "ok.gltf");
  EXPECT_EQ(s.instances.size(), 1u);
  EXPECT_NEAR(s.meshes[0].vertices[0].normal.z, 1.0f, 1e-6f);  // generated from the winding
}

TEST(SceneErrors, MissingFile) { expectOneLineErrorNaming("/nonexistent/dir/nothing.gltf", "file not found"); }

TEST(SceneErrors, NotJson) {
  TempDir tmp;
  writeText(tmp.path / "not_json.gltf", "this is not { json");
  expectOneLineErrorNaming(tmp.path / "not_json.gltf", "not a valid glTF file");
}

TEST(SceneErrors, TruncatedGlb) {
  TempDir tmp;
  writeText(tmp.path / "truncated.glb", std::string("glTF\x02\x00\x00\x00\x40\x00", 10));
  expectOneLineErrorNaming(tmp.path / "truncated.glb", "not a valid glTF file");
}

TEST(SceneErrors, MissingBinary) {
  TempDir tmp;
  writeText(tmp.path / "missing_bin.gltf", triangle("nowhere.bin").dump());
  expectOneLineErrorNaming(tmp.path / "missing_bin.gltf", "not a valid glTF file");
}

TEST(SceneErrors, AccessorOutOfRange) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["accessors"][0]["count"] = 300;  // far past the 36-byte view
  writeText(tmp.path / "accessor_out_of_range.gltf", j.dump());
  expectOneLineErrorNaming(tmp.path / "accessor_out_of_range.gltf", "accessor 0 (POSITION) reaches past the end");
}

TEST(SceneErrors, IndexOutOfRange) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin", 60000);
  writeText(tmp.path / "index_out_of_range.gltf", triangle("t.bin").dump());
  expectOneLineErrorNaming(tmp.path / "index_out_of_range.gltf", "index 2 is 60000, beyond its 3 vertices");
}

TEST(SceneErrors, MissingPosition) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
  writeText(tmp.path / "no_position.gltf", j.dump());
  expectOneLineErrorNaming(tmp.path / "no_position.gltf", "has no POSITION");
}

TEST(SceneErrors, UnsupportedRequiredExtension) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  writeText(tmp.path / "draco_required.gltf", j.dump());
  expectOneLineErrorNaming(tmp.path / "draco_required.gltf", "KHR_draco_mesh_compression");
}

// The material extensions exporters write: KHR_materials_ior and KHR_materials_specular reach
// the material as authored, KHR_materials_unlit marks it, and a file that requires
// KHR_materials_pbrSpecularGlossiness is converted to metal-rough (no longer refused), with the
// conversion's error stated. Out-of-range values are clamped with a warning each.
TEST(SceneImport, MaterialExtensionsAreReadAndSpecularGlossinessIsConverted) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["extensionsUsed"] = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_unlit",
                         "KHR_materials_pbrSpecularGlossiness"};
  j["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
  j["materials"] = {
      {{"name", "tinted"},
       {"extensions",
        {{"KHR_materials_ior", {{"ior", 2.0}}},
         {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 0.25}}}}}}},
      {{"name", "flat"}, {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}},
      {{"name", "plastic"},
       {"extensions",
        {{"KHR_materials_pbrSpecularGlossiness",
          {{"diffuseFactor", {0.5, 0.25, 0.125, 1.0}}, {"specularFactor", {0.04, 0.04, 0.04}}, {"glossinessFactor", 0.75}}}}}},
      {{"name", "gold"},
       {"extensions",
        {{"KHR_materials_pbrSpecularGlossiness",
          {{"diffuseFactor", {0.0, 0.0, 0.0, 1.0}}, {"specularFactor", {1.0, 0.78, 0.34}}, {"glossinessFactor", 0.9}}}}}},
      {{"name", "out_of_range"},
       {"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}, {"KHR_materials_specular", {{"specularFactor", 2.0}}}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  writeText(tmp.path / "extensions.gltf", j.dump());
  const Scene s = loadGltf(tmp.path / "extensions.gltf");
  ASSERT_EQ(s.materials.size(), 5u);
  const Material& tinted = s.materials[0];
  EXPECT_FLOAT_EQ(tinted.ior, 2.0f);
  EXPECT_FLOAT_EQ(tinted.specularFactor, 0.5f);
  EXPECT_FLOAT_EQ(tinted.specularColorFactor.g, 0.5f);
  EXPECT_FALSE(tinted.unlit);
  EXPECT_TRUE(s.materials[1].unlit);
  // A grey plastic's specular is the model's 0.04: nothing to approximate.
  const Material& plastic = s.materials[2];
  EXPECT_NEAR(plastic.metallic, 0.0f, 1e-6f);
  EXPECT_NEAR(plastic.baseColorFactor.r, 0.5f, 1e-5f);
  EXPECT_NEAR(plastic.baseColorFactor.b, 0.125f, 1e-5f);
  EXPECT_NEAR(plastic.roughness, 0.25f, 1e-6f);
  EXPECT_LT(plastic.specularGlossinessError, 1e-5f);
  // Gold: a black diffuse and a coloured specular are a metal of that colour.
  const Material& gold = s.materials[3];
  EXPECT_GT(gold.metallic, 0.99f);
  EXPECT_NEAR(gold.baseColorFactor.g, 0.78f, 0.01f);
  EXPECT_NEAR(gold.roughness, 0.1f, 1e-6f);
  std::printf("specular-glossiness: plastic error %.5f, gold error %.5f (metallic %.4f)\n", plastic.specularGlossinessError,
              gold.specularGlossinessError, gold.metallic);
  EXPECT_LT(gold.specularGlossinessError, 0.02f);
  EXPECT_FLOAT_EQ(s.materials[4].ior, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[4].specularFactor, 1.0f);
  size_t clampWarnings = 0;
  for (const auto& w : s.warnings) clampWarnings += w.find("out_of_range") != std::string::npos;
  EXPECT_EQ(clampWarnings, 2u);
  bool converted = false, tintedNoted = false;
  for (const auto& i : s.ignored) {
    EXPECT_EQ(i.find("not applied"), std::string::npos) << i;
    converted |= i.find("KHR_materials_pbrSpecularGlossiness (2x): converted to metal-rough") == 0;
    tintedNoted |= i.find("tinted KHR_materials_specular colour (1x)") != std::string::npos;
  }
  EXPECT_TRUE(converted);
  EXPECT_TRUE(tintedNoted);
  // The report names how each extension is rendered.
  const auto report = sceneReport(s);
  for (const char* line : {"extension KHR_materials_ior: rendered", "extension KHR_materials_unlit: rendered",
                           "extension KHR_materials_pbrSpecularGlossiness: converted to metal-rough"})
    EXPECT_TRUE(std::any_of(report.begin(), report.end(), [&](const std::string& l) { return l.rfind(line, 0) == 0; })) << line;
}

// KHR_materials_transmission, _volume and _clearcoat reach the material as authored; a
// transmission above 1 is clamped with a warning, and an attenuationDistance that is not
// positive is one clear error.
TEST(SceneImport, TransmissionAndVolumeAreRead) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_clearcoat"};
  j["materials"] = {
      {{"name", "window"},
       {"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
         {"KHR_materials_clearcoat", {{"clearcoatFactor", 0.5}, {"clearcoatRoughnessFactor", 0.25}}}}}},
      {{"name", "bottle"},
       {"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}},
         {"KHR_materials_volume",
          {{"thicknessFactor", 0.2}, {"attenuationColor", {0.5, 0.8, 1.0}}, {"attenuationDistance", 0.25}}}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 1;
  writeText(tmp.path / "glass.gltf", j.dump());
  const Scene s = loadGltf(tmp.path / "glass.gltf");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_FLOAT_EQ(s.materials[0].transmission, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[0].thickness, 0.0f);
  EXPECT_TRUE(std::isinf(s.materials[0].attenuationDistance));
  EXPECT_FLOAT_EQ(s.materials[0].clearcoat, 0.5f);
  EXPECT_FLOAT_EQ(s.materials[0].clearcoatRoughness, 0.25f);
  EXPECT_FLOAT_EQ(s.materials[1].clearcoat, 0.0f);
  const Material& bottle = s.materials[1];
  EXPECT_FLOAT_EQ(bottle.transmission, 1.0f);
  EXPECT_FLOAT_EQ(bottle.thickness, 0.2f);
  EXPECT_FLOAT_EQ(bottle.attenuationColor.g, 0.8f);
  EXPECT_FLOAT_EQ(bottle.attenuationDistance, 0.25f);
  EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(),
                          [](const std::string& w) { return w.find("transmissionFactor") != std::string::npos; }));
  for (const auto& i : s.ignored) EXPECT_EQ(i.find("not applied"), std::string::npos) << i;
  const auto report = sceneReport(s);
  for (const char* line : {"materials: 2 (2 opaque; 2 transmitting, 1 of them bounding a volume)",
                           "extension KHR_materials_transmission: rendered", "extension KHR_materials_volume: rendered",
                           "extension KHR_materials_clearcoat: rendered"})
    EXPECT_TRUE(std::any_of(report.begin(), report.end(), [&](const std::string& l) { return l.rfind(line, 0) == 0; }))
        << line;

  j["materials"][1]["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 0.0;
  writeText(tmp.path / "bad_distance.gltf", j.dump());
  expectOneLineErrorNaming(tmp.path / "bad_distance.gltf", "attenuationDistance");
}

TEST(SceneErrors, NonFinitePosition) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin", 2, {0, 0, 0, NAN, 0, 0, 0, 1, 0});
  writeText(tmp.path / "nan.gltf", triangle("t.bin").dump());
  expectOneLineErrorNaming(tmp.path / "nan.gltf", "non-finite position");
}

TEST(SceneErrors, MissingTextureIsAWarningAndAPlaceholder) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto j = triangle("t.bin");
  j["images"] = {{{"uri", "textures/gone.png"}}};
  j["textures"] = {{{"source", 0}}};
  j["materials"] = {{{"name", "m"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  writeText(tmp.path / "missing_texture.gltf", j.dump());
  Scene s = loadGltf(tmp.path / "missing_texture.gltf");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("gone.png"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("missing_texture.gltf"), std::string::npos) << s.warnings[0];
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_TRUE(s.textures[0].placeholder);
  EXPECT_EQ(s.textures[0].rgba8[0], 255);  // magenta
  EXPECT_EQ(s.textures[0].rgba8[1], 0);
}

TEST(SceneErrors, DegenerateTrianglesGiveFiniteNormals) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin", 2, {1, 1, 1, 1, 1, 1, 1, 1, 1});  // zero area
  writeText(tmp.path / "degenerate.gltf", triangle("t.bin").dump());
  Scene s = loadGltf(tmp.path / "degenerate.gltf");
  for (auto& v : s.meshes[0].vertices) {
    EXPECT_TRUE(std::isfinite(v.normal.x) && std::isfinite(v.tangent.x));
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
  }
}

}  // namespace
// ---- KHR_lights_punctual ------------------------------------------------------------------

// The triangle with lights: two directional lights, a point light and a spot light, each on
// its own node (the spot at (0, 3, 0) turned to shine down -Y).
nlohmann::json triangleWithLights() {
  auto j = triangle("t.bin");
  j["extensionsUsed"] = {"KHR_lights_punctual"};
  j["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "directional"}, {"name", "sun"}, {"intensity", 683.0 * 5.0}},
      {{"type", "directional"}, {"name", "fill"}, {"intensity", 683.0}, {"color", {1.0, 0.5, 0.25}}},
      {{"type", "point"}, {"name", "bulb"}, {"intensity", 100.0}, {"range", 8.0}},
      {{"type", "spot"}, {"name", "spot"}, {"intensity", 683.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}}};
  const double s = std::sqrt(0.5);  // a rotation of -90 degrees about x: -Z becomes -Y
  j["nodes"] = {{{"mesh", 0}},
                {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                {{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
                {{"translation", {1.0, 2.0, 3.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}},
                {{"translation", {0.0, 3.0, 0.0}}, {"rotation", {-s, 0.0, 0.0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 3}}}}}}};
  j["scenes"][0]["nodes"] = {0, 1, 2, 3, 4};
  return j;
}

TEST(SceneLights, EveryLightIsReadInItsUnitsAndTheFirstDirectionalIsTheSun) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  writeText(tmp.path / "lights.gltf", triangleWithLights().dump());
  Scene s = loadGltf(tmp.path / "lights.gltf");
  ASSERT_EQ(s.lights.size(), 4u);
  ASSERT_TRUE(s.environment.sunLight);
  EXPECT_EQ(*s.environment.sunLight, 0u);
  // 683 x 5 lux is E = 5 on Twinlight's scale: a Blender sun of strength 5 exported with its
  // default (physical) conversion next to a world of strength 5.
  EXPECT_NEAR(s.environment.sunIrradiance.x, 5.0f, 1e-5f);
  EXPECT_EQ(s.lights[1].type, LightType::Directional);
  EXPECT_NEAR(s.lights[1].radiometric().y, 0.5f, 1e-6f);  // 683 lux, colour 0.5
  EXPECT_EQ(s.lights[2].type, LightType::Point);
  EXPECT_NEAR(s.lights[2].intensity, 100.0f, 0.0f);
  EXPECT_NEAR(s.lights[2].radiometric().x, 100.0f / 683.0f, 1e-7f);
  ASSERT_TRUE(s.lights[2].range);
  EXPECT_EQ(*s.lights[2].range, 8.0f);
  EXPECT_NEAR(s.lights[2].position.x, 1.0, 1e-12);
  EXPECT_NEAR(s.lights[2].position.z, 3.0, 1e-12);
  EXPECT_EQ(s.lights[3].type, LightType::Spot);
  EXPECT_NEAR(s.lights[3].innerConeAngle, 0.2f, 1e-7f);
  EXPECT_NEAR(s.lights[3].outerConeAngle, 0.6f, 1e-7f);
  EXPECT_NEAR(s.lights[3].direction.y, -1.0, 1e-9);  // its node turned -Z to -Y
  // The lights are part of the content: moving one changes the scene's hash.
  auto j = triangleWithLights();
  j["nodes"][3]["translation"] = {1.0, 2.5, 3.0};
  writeText(tmp.path / "moved.gltf", j.dump());
  EXPECT_NE(loadGltf(tmp.path / "moved.gltf").contentHash, s.contentHash);
}

TEST(SceneLights, LightsAgainstTheSpecificationAreOneClearError) {
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto cones = triangleWithLights();
  cones["extensions"]["KHR_lights_punctual"]["lights"][3]["spot"]["innerConeAngle"] = 0.7;
  writeText(tmp.path / "cones.gltf", cones.dump());
  expectOneLineErrorNaming(tmp.path / "cones.gltf", "cone angles");
  auto outside = triangleWithLights();
  outside["extensions"]["KHR_lights_punctual"]["lights"][3]["spot"]["outerConeAngle"] = 2.0;
  writeText(tmp.path / "outside.gltf", outside.dump());
  expectOneLineErrorNaming(tmp.path / "outside.gltf", "cone angles");
  auto type = triangleWithLights();
  type["extensions"]["KHR_lights_punctual"]["lights"][2]["type"] = "area";
  writeText(tmp.path / "type.gltf", type.dump());
  expectOneLineErrorNaming(tmp.path / "type.gltf", "has type `area`");
  auto missing = triangleWithLights();
  missing["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 9;
  writeText(tmp.path / "missing.gltf", missing.dump());
  expectOneLineErrorNaming(tmp.path / "missing.gltf", "refers to light 9");
}

TEST(SceneLights, NegativeLightIsNoLightWithOneWarning) {
  // The import's rule for plain out-of-range values (scene/import_values.h): clamped, warned.
  TempDir tmp;
  writeTriangleBin(tmp.path / "t.bin");
  auto negative = triangleWithLights();
  negative["extensions"]["KHR_lights_punctual"]["lights"][2]["intensity"] = -1.0;
  writeText(tmp.path / "negative.gltf", negative.dump());
  const Scene s = loadGltf(tmp.path / "negative.gltf");
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[2].intensity, 0.0f);
  size_t naming = 0;
  for (const auto& w : s.warnings) naming += w.find("light `bulb` intensity is negative") != std::string::npos;
  EXPECT_EQ(naming, 1u);
}

}  // namespace tl::scene
