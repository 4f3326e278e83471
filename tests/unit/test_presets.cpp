// Built-in and artist presets of render settings (session/presets.h).
#include "session/presets.h"
#include "session/settings_json.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace tl::session {
namespace {

TEST(Presets, EveryPathHasFastBalancedAndReferenceLikeThroughTheSchema) {
  std::set<std::pair<std::string, std::string>> seen;
  for (const Preset& p : builtInPresets()) {
    seen.insert({p.path, p.name});
    // Every value parses through the schema, and the preset's values are what it leaves.
    const lighting::RenderSettings s = applyPreset(lighting::RenderSettings{}, p);
    for (const auto& [name, value] : p.values) {
      const lighting::SettingInfo* info = lighting::findSetting(name);
      ASSERT_NE(info, nullptr) << name;
      EXPECT_EQ(lighting::formatSetting(*info, info->get(s)), lighting::formatSetting(*info, lighting::parseSetting(*info, value)))
          << p.path << " " << p.name << " " << name;
    }
  }
  for (const char* path : {"direct", "legacy", "rt", "reference"})
    for (const char* name : {"Fast", "Balanced", "Reference-like"}) EXPECT_TRUE(seen.count({path, name})) << path << " " << name;
}

TEST(Presets, PresetsDoNotStackAndBalancedIsTheDefaults) {
  const auto& all = builtInPresets();
  auto find = [&](const std::string& path, const std::string& name) {
    for (const Preset& p : all)
      if (p.path == path && p.name == name) return p;
    throw std::runtime_error("no preset");
  };
  lighting::RenderSettings s;
  s.shadowMapSize = 512;  // a common setting the rt presets do not name stays
  s = applyPreset(s, find("rt", "Reference-like"));
  EXPECT_TRUE(s.rtTwoRays);
  s = applyPreset(s, find("rt", "Fast"));
  EXPECT_TRUE(s.rtHalfResolution);
  EXPECT_FALSE(s.rtTwoRays) << "Fast after Reference-like is Fast, not both";
  s = applyPreset(s, find("rt", "Balanced"));
  EXPECT_EQ(session::settingsJson(s).dump(), [] {
    lighting::RenderSettings d;
    d.shadowMapSize = 512;
    return session::settingsJson(d).dump();
  }());
}

TEST(Presets, AsCompareSettingsEachPresetIsItsOwnValuesTyped) {
  for (const Preset& p : builtInPresets()) {
    const nlohmann::json j = presetSettingsJson(p);
    EXPECT_EQ(j.size(), p.values.size()) << p.path << " " << p.name;
    // Applied to the defaults, the object gives what the preset gives.
    EXPECT_EQ(settingsJson(applySettingsJson(lighting::RenderSettings{}, j)).dump(),
              settingsJson(applyPreset(lighting::RenderSettings{}, p)).dump())
        << p.path << " " << p.name;
  }
  const auto& all = builtInPresets();
  auto fast = std::find_if(all.begin(), all.end(), [](const Preset& p) { return p.path == "direct" && p.name == "Fast"; });
  ASSERT_NE(fast, all.end());
  EXPECT_EQ(presetSettingsJson(*fast), (nlohmann::json{{"shadowMapSize", 1024}, {"softShadows", false}}));
}

TEST(Presets, AnArtistsPresetRoundTripsWithoutTheImageSize) {
  const auto file = std::filesystem::path(::testing::TempDir()) / "twinlight_presets" / "mine.json";
  lighting::RenderSettings s;
  s.width = 1234;
  s.rtDenoise = false;
  s.legacyConeStep = 0.75f;
  savePresetFile(file, s);
  const nlohmann::json j = readSettingsFile(file);
  EXPECT_FALSE(j.contains("width"));
  EXPECT_FALSE(j.contains("height"));
  const lighting::RenderSettings back = loadPresetFile(file, lighting::RenderSettings{});
  EXPECT_FALSE(back.rtDenoise);
  EXPECT_FLOAT_EQ(back.legacyConeStep, 0.75f);
  EXPECT_EQ(back.width, lighting::RenderSettings{}.width);
}

}  // namespace
}  // namespace tl::session
