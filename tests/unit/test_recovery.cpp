// The editor's recovery file (session/recovery.h): unsaved work written and read back as it was,
// a damaged file one clear error, and removal taking both of its files.
#include "../common/temp_dir.h"
#include "session/edit_history.h"
#include "session/recovery.h"
#include "session/settings_json.h"

#include <gtest/gtest.h>

#include <fstream>

namespace tl::session {
namespace {

namespace fs = std::filesystem;

RecoveredWork someWork() {
  RecoveredWork w;
  w.scene = "/scenes/lamps.gltf";
  w.savedAt = "2024-06-11T10:00:00Z";
  Lighting l;
  l.sunDirection = glm::normalize(glm::dvec3(-0.4, -1.0, -0.3));  // as a scene's (a file holds unit directions)
  l.sunIrradiance = {3.0f, 2.5f, 2.0f};
  l.exposureEv = 1.5f;
  scene::Light bulb;
  bulb.name = "bulb";
  bulb.position = {1.0, 2.0, 3.0};
  bulb.intensity = 80.0f;
  bulb.hidden = true;
  l.lights.push_back(bulb);
  w.lighting = l;
  lighting::RenderSettings s;
  s.shadowMapSize = 1024;
  w.settings = settingsJson(s);
  w.overrides.push_back({0x0123456789abcdefull, glm::vec3(0.8f, 0.2f, 0.1f), "floor / painted"});
  w.overrides.push_back({0xfedcba9876543210ull, std::nullopt, "wall / plaster"});
  return w;
}

TEST(Recovery, UnsavedWorkReadsBackAsItWasWritten) {
  test::TempDir dir;
  const fs::path file = recoveryFile(dir.path / "recovery", "/scenes/lamps.gltf");
  EXPECT_NE(file, recoveryFile(dir.path / "recovery", "/other/lamps.gltf")) << "two scenes of one name";
  const RecoveredWork w = someWork();
  writeRecovery(file, w);
  const RecoveredWork r = readRecovery(file);
  EXPECT_EQ(r.scene, w.scene);
  EXPECT_EQ(r.savedAt, w.savedAt);
  ASSERT_TRUE(r.lighting.has_value());
  EXPECT_TRUE(sameLighting(*r.lighting, *w.lighting));
  ASSERT_TRUE(r.settings.has_value());
  EXPECT_EQ(applySettingsJson({}, *r.settings).shadowMapSize, 1024u);
  ASSERT_EQ(r.overrides.size(), 2u);
  EXPECT_EQ(r.overrides[0].key, w.overrides[0].key);
  EXPECT_EQ(r.overrides[0].rgb, w.overrides[0].rgb);
  EXPECT_EQ(r.overrides[0].label, "floor / painted");
  EXPECT_FALSE(r.overrides[1].rgb.has_value()) << "a cleared override stays cleared";
  EXPECT_FALSE(r.empty());

  removeRecovery(file);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_empty(file.parent_path())) << "its lighting file goes with it";
}

TEST(Recovery, OnlyWhatWasUnsavedIsHeld) {
  test::TempDir dir;
  const fs::path file = dir.path / "x.recovery.json";
  RecoveredWork w;
  w.scene = "/scenes/x.gltf";
  w.overrides.push_back({42, glm::vec3(0.5f), "a / b"});
  writeRecovery(file, w);
  const RecoveredWork r = readRecovery(file);
  EXPECT_FALSE(r.lighting.has_value());
  EXPECT_FALSE(r.settings.has_value());
  EXPECT_EQ(r.overrides.size(), 1u);
}

TEST(Recovery, ADamagedFileIsOneErrorNamingIt) {
  test::TempDir dir;
  const fs::path file = dir.path / "x.recovery.json";
  writeRecovery(file, someWork());
  const auto refusedWith = [&](const std::string& text, const std::string& expected) {
    std::ofstream(file) << text;
    try {
      readRecovery(file);
    } catch (const SessionError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string()), std::string::npos) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << what;
      return;
    }
    ADD_FAILURE() << "accepted: " << text;
  };
  refusedWith("{", "not JSON");
  refusedWith("{\"format\": \"twinlight.lighting\", \"version\": 1}", "not a recovery file");
  refusedWith("{\"format\": \"twinlight.recovery\", \"version\": 1}", "scene");
  refusedWith("{\"format\": \"twinlight.recovery\", \"version\": 1, \"scene\": \"a.gltf\", \"overrides\": [{\"key\": \"12\"}]}",
              "overrides[0].key");
  refusedWith("{\"format\": \"twinlight.recovery\", \"version\": 1, \"scene\": \"a.gltf\", \"overrides\": "
              "[{\"key\": \"0123456789abcdef\", \"rgb\": [1, -2, 0]}]}",
              "overrides[0].rgb");
  refusedWith("{\"format\": \"twinlight.recovery\", \"version\": 1, \"scene\": \"a.gltf\", \"settings\": {\"shadowMapSize\": 3}}",
              "shadowMapSize");
  refusedWith("{\"format\": \"twinlight.recovery\", \"version\": 1, \"scene\": \"a.gltf\", \"lighting\": \"gone.json\"}", "gone.json");
}

}  // namespace
}  // namespace tl::session
