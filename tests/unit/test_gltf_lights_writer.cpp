// Saving lights into an artist's glTF (session/gltf_lights_writer.h, saveSceneLighting): what is
// written loads back as the same lights through the importer, nothing else of the file changes,
// a second save of the same lights writes the same bytes, and a failure leaves the file alone.
#include "../common/temp_dir.h"
#include "scene/scene.h"
#include "session/edit_history.h"
#include "session/gltf_lights_writer.h"
#include "session/lighting_file.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace tl::session {
namespace {

namespace fs = std::filesystem;
using scene::Light;
using scene::LightType;

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expectSameLight(const Light& saved, const Light& loaded) {
  SCOPED_TRACE(saved.name);
  EXPECT_EQ(loaded.name, saved.name);
  EXPECT_EQ(loaded.type, saved.type);
  EXPECT_NEAR(loaded.intensity, saved.intensity, 1e-4 * saved.intensity);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded.color[c], saved.color[c], 1e-6);
  // A directional light's position is its icon's in the editor: kept like the others'.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(loaded.position[c], saved.position[c], 1e-9);
  if (saved.type != LightType::Point) {
    EXPECT_GT(glm::dot(loaded.direction, glm::normalize(saved.direction)), 1.0 - 1e-12);
  }
  EXPECT_EQ(loaded.range.has_value(), saved.range.has_value());
  if (saved.type == LightType::Spot) {
    EXPECT_NEAR(loaded.innerConeAngle, saved.innerConeAngle, 1e-6);
    EXPECT_NEAR(loaded.outerConeAngle, saved.outerConeAngle, 1e-6);
  }
}

class GltfLightsWriterTest : public ::testing::Test {
 protected:
  test::TempDir scratch;
  // A copy of a content scene (with its buffer) the test may change.
  fs::path copyOf(const std::string& name) {
    const fs::path from = fs::path(TWINLIGHT_CONTENT_DIR) / name;
    fs::copy_file(from, scratch.path / name);
    fs::path bin = from;
    bin.replace_extension(".bin");
    if (fs::exists(bin)) fs::copy_file(bin, scratch.path / bin.filename());
    return scratch.path / name;
  }
};

TEST_F(GltfLightsWriterTest, MovedAddedAndDeletedLightsLoadBackAsSavedAndTheRestIsUntouched) {
  const fs::path file = copyOf("lamps.gltf");
  const scene::Scene before = scene::loadGltf(file);
  ASSERT_EQ(before.lights.size(), 3u);
  std::vector<Light> lights = before.lights;
  lights.erase(lights.begin() + 1);  // bulb_corner deleted
  lights[0].position += glm::dvec3(0.25, -0.5, 1.0);  // bulb_table moved
  lights[1].direction = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));  // spot_sphere turned
  lights[1].outerConeAngle = 0.7f;
  Light added;
  added.name = "new spot";
  added.type = LightType::Spot;
  added.position = {0.5, 2.0, -0.5};
  added.direction = {0.0, 0.0, 1.0};  // straight along +Z: the opposite of a light's rest direction
  added.intensity = 123.0f;
  added.color = {0.2f, 0.4f, 1.0f};
  added.range = 7.5f;
  lights.push_back(added);
  Light fill;  // a directional light whose icon the artist put in a corner of the room
  fill.name = "fill";
  fill.type = LightType::Directional;
  fill.position = {1.5, 2.5, -1.0};
  fill.direction = glm::normalize(glm::dvec3(0.2, -1.0, 0.4));
  fill.intensity = 2.0f;
  lights.push_back(fill);

  const std::vector<uint32_t> nodes = writeGltfLights(file, lights);
  ASSERT_EQ(nodes.size(), 4u);
  EXPECT_EQ(nodes[0], *before.lights[0].node);  // written back into their own nodes
  EXPECT_EQ(nodes[1], *before.lights[2].node);
  const scene::Scene after = scene::loadGltf(file);
  ASSERT_EQ(after.lights.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const Light& saved = lights[i];
    const Light* loaded = nullptr;
    for (const auto& l : after.lights)
      if (l.name == saved.name) loaded = &l;
    ASSERT_NE(loaded, nullptr) << saved.name;
    expectSameLight(saved, *loaded);
    // And the editor calls it the light it saved: nothing unsaved after a file read back.
    EXPECT_TRUE(sameLight(saved, *loaded)) << saved.name;
  }
  // The rest of the scene is the scene it was.
  EXPECT_EQ(after.instances.size(), before.instances.size());
  EXPECT_EQ(after.materials.size(), before.materials.size());
  EXPECT_EQ(after.bounds.min, before.bounds.min);
  EXPECT_EQ(after.bounds.max, before.bounds.max);
  EXPECT_TRUE(after.warnings.empty()) << after.warnings.front();
  // Two nodes were added (the new spot, the fill); the deleted light's node stays, without its light.
  EXPECT_EQ(after.nodes.size(), before.nodes.size() + 2);

  // Saving the lights as loaded again changes nothing, to the byte, and adds no node.
  const std::string once = readBytes(file);
  std::vector<Light> again = lights;
  for (size_t i = 0; i < again.size(); ++i) again[i].node = nodes[i];
  EXPECT_EQ(writeGltfLights(file, again), nodes);
  EXPECT_EQ(readBytes(file), once);
}

TEST_F(GltfLightsWriterTest, AGlbKeepsItsBinaryChunkByteForByte) {
  const fs::path file = copyOf("embedded_textures.glb");
  const std::string original = readBytes(file);
  const scene::Scene before = scene::loadGltf(file);
  ASSERT_TRUE(before.lights.empty());
  Light lamp;
  lamp.name = "lamp";
  lamp.position = {0.0, 1.5, 0.5};
  lamp.intensity = 40.0f;
  writeGltfLights(file, {lamp});
  const std::string written = readBytes(file);
  uint32_t oldJson = 0, newJson = 0, total = 0;
  std::memcpy(&oldJson, original.data() + 12, 4);
  std::memcpy(&newJson, written.data() + 12, 4);
  std::memcpy(&total, written.data() + 8, 4);
  EXPECT_EQ(total, written.size());
  EXPECT_EQ(newJson % 4, 0u);
  EXPECT_EQ(written.substr(20 + newJson), original.substr(20 + oldJson));  // the BIN chunk
  const scene::Scene after = scene::loadGltf(file);
  ASSERT_EQ(after.lights.size(), 1u);
  expectSameLight(lamp, after.lights[0]);
  EXPECT_EQ(after.textures.size(), before.textures.size());
  EXPECT_EQ(after.instances.size(), before.instances.size());
  // Without lights the extension leaves the file (and its list of extensions used).
  writeGltfLights(file, {});
  EXPECT_TRUE(scene::loadGltf(file).lights.empty());
  const std::string cleared = readBytes(file);
  EXPECT_EQ(cleared.find("KHR_lights_punctual"), std::string::npos);
}

// A light on a node under a scaled, turned and moved parent stays where it was put.
TEST_F(GltfLightsWriterTest, ALightUnderATransformedParentLandsWhereItWasPut) {
  const fs::path file = scratch.path / "parented.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 10, "spot": {"outerConeAngle": 0.5}}]}},
    "nodes": [{"name": "rig", "translation": [1, 2, 3], "rotation": [0, 0.3826834, 0, 0.9238795], "scale": [2, 2, 2],
               "children": [1]},
              {"name": "spot", "translation": [0.5, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}]})";
  const scene::Scene before = scene::loadGltf(file);
  ASSERT_EQ(before.lights.size(), 1u);
  std::vector<Light> lights = before.lights;
  lights[0].name = "spot";
  lights[0].position = {-3.0, 0.5, 4.0};
  lights[0].direction = glm::normalize(glm::dvec3(1.0, -2.0, 0.5));
  EXPECT_EQ(writeGltfLights(file, lights), std::vector<uint32_t>{1});
  const scene::Scene after = scene::loadGltf(file);
  ASSERT_EQ(after.lights.size(), 1u);
  expectSameLight(lights[0], after.lights[0]);
  EXPECT_EQ(after.nodes.size(), 2u);
}

TEST_F(GltfLightsWriterTest, AnAreaLightOrABrokenFileIsOneErrorAndTheFileStaysAsItWas) {
  const fs::path file = copyOf("lamps.gltf");
  const std::string original = readBytes(file);
  Light rect;
  rect.name = "panel";
  rect.type = LightType::Rect;
  EXPECT_THROW(writeGltfLights(file, {rect}), SessionError);
  EXPECT_EQ(readBytes(file), original);
  const fs::path broken = scratch.path / "broken.gltf";
  std::ofstream(broken) << "{\"asset\": ";
  try {
    writeGltfLights(broken, {});
    ADD_FAILURE() << "a file that is not JSON was written";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.gltf"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readBytes(broken), "{\"asset\": ");
  // JSON, but a value of another type than glTF gives it: one error, the file as it was.
  const fs::path odd = scratch.path / "odd.gltf";
  const std::string oddText = R"({"asset": {"version": "2.0"}, "extensions": 3, "nodes": []})";
  std::ofstream(odd) << oddText;
  Light lamp;
  lamp.name = "lamp";
  EXPECT_THROW(writeGltfLights(odd, {lamp}), SessionError);
  EXPECT_EQ(readBytes(odd), oddText);
}

// The editor's save: the sun and the shown punctual lights into the glTF, everything into the
// sidecar; loading the glTF again gives the same sun (lux on glTF's scale), the sidecar the
// area and hidden lights too.
TEST_F(GltfLightsWriterTest, SavingASceneWritesTheSunAndShownLightsIntoTheGltfAndAllIntoTheSidecar) {
  const fs::path file = copyOf("lamps.gltf");
  const scene::Scene loaded = scene::loadGltf(file);
  Lighting l;
  l.sunDirection = glm::normalize(glm::dvec3(0.2, -1.0, 0.4));
  l.sunIrradiance = {6.0f, 5.0f, 4.0f};
  l.lights = loaded.lights;
  l.lights[1].hidden = true;
  Light panel;
  panel.name = "panel";
  panel.type = LightType::Rect;
  panel.position = {0.0, 2.5, 0.0};
  panel.direction = {0.0, -1.0, 0.0};
  panel.intensity = 500.0f;
  l.lights.push_back(panel);

  const SavedLighting saved = saveSceneLighting(file, l);
  EXPECT_EQ(saved.gltfLights, 3u);  // the sun, bulb_table, spot_sphere
  EXPECT_EQ(saved.sidecar, scratch.path / "lamps.lighting.json");
  ASSERT_TRUE(l.sunNode.has_value());
  EXPECT_FALSE(l.lights[1].node.has_value());  // hidden: no node holds it
  EXPECT_FALSE(l.lights[3].node.has_value());  // an area light: the sidecar's alone

  const scene::Scene again = scene::loadGltf(file);
  ASSERT_EQ(again.lights.size(), 3u);
  ASSERT_TRUE(again.environment.sunLight.has_value());
  EXPECT_EQ(*again.environment.sunLight, 0u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(again.environment.sunIrradiance[c], l.sunIrradiance[c], 1e-5);
  EXPECT_GT(glm::dot(again.environment.sunDirection, l.sunDirection), 1.0 - 1e-12);
  expectSameLight(l.lights[0], again.lights[1]);
  expectSameLight(l.lights[2], again.lights[2]);

  const Lighting side = readLightingFile(saved.sidecar, Lighting{});
  ASSERT_EQ(side.lights.size(), 4u);
  EXPECT_TRUE(side.lights[1].hidden);
  EXPECT_EQ(side.lights[3].type, LightType::Rect);
  EXPECT_EQ(side.sunNode, l.sunNode);
  EXPECT_EQ(side.lights[0].node, l.lights[0].node);
  // Saved twice without a change: the same two files.
  const std::string gltf = readBytes(file), sidecar = readBytes(saved.sidecar);
  saveSceneLighting(file, l);
  EXPECT_EQ(readBytes(file), gltf);
  EXPECT_EQ(readBytes(saved.sidecar), sidecar);
}

}  // namespace
}  // namespace tl::session
