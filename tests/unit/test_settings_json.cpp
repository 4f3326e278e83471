// Render settings from JSON: known keys apply, unknown keys and wrong types are one clear error.
#include "lighting/lighting_path.h"
#include "session/session.h"
#include "session/settings_json.h"
#include "session/settings_reference.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>

namespace tl::session {
namespace {

TEST(SettingsJson, KnownKeysApplyAndTheRestIsKept) {
  lighting::RenderSettings base;
  auto s = applySettingsJson(base, {{"rtHalfRays", true}, {"legacyConeDivisor", 2}, {"rtAoRadius", 0.5}});
  EXPECT_TRUE(s.rtHalfRays);
  EXPECT_EQ(s.legacyConeDivisor, 2u);
  EXPECT_FLOAT_EQ(s.rtAoRadius, 0.5f);
  EXPECT_EQ(s.width, base.width);
  EXPECT_EQ(s.rtDenoise, base.rtDenoise);
}

TEST(SettingsJson, UnknownKeysAndWrongTypesAreRefusedByName) {
  lighting::RenderSettings base;
  try {
    applySettingsJson(base, {{"rtBogus", 1}});
    FAIL() << "accepted an unknown key";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown setting `rtBogus`"), std::string::npos) << e.what();
  }
  try {
    applySettingsJson(base, {{"rtHalfRays", 3}});
    FAIL() << "accepted a number for a switch";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("`rtHalfRays` must be true or false"), std::string::npos) << e.what();
  }
  EXPECT_THROW(applySettingsJson(base, {{"legacyAoSteps", -2}}), SessionError);
  EXPECT_THROW(applySettingsJson(base, nlohmann::json::array()), SessionError);
}

// Values are range-checked before they are converted (shadowMapSize 0 or 65536 gave
// validation errors and exit 0; 4294967297 was truncated to 1; rtPretraceSteps 4000000000
// never ended).
TEST(SettingsJson, ValuesOutsideTheirStatedRangeAreRefused) {
  lighting::RenderSettings base;
  auto message = [&](const nlohmann::json& j) {
    try {
      applySettingsJson(base, j);
    } catch (const SessionError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  for (const char* key : {"shadowMapSize"})
    for (const nlohmann::json& v : {nlohmann::json(0), nlohmann::json(65536), nlohmann::json(4294967297ull), nlohmann::json(-1)})
      EXPECT_EQ(message({{key, v}}), fmt::format("setting `shadowMapSize` must be a whole number from 64 to 8192, not {}", v.dump()));
  EXPECT_EQ(message({{"rtPretraceSteps", 4000000000ull}}),
            "setting `rtPretraceSteps` must be a whole number from 1 to 256, not 4000000000");
  EXPECT_EQ(message({{"legacyConeStep", 0}}), "setting `legacyConeStep` must be a number from 0.2 to 2, not 0");
  EXPECT_EQ(message({{"rtAoRadius", 1e39}}), "setting `rtAoRadius` must be a number from 0 to 1e+09, not 1e+39");
  EXPECT_EQ(message({{"legacyAoSteps", 2.5}}), "setting `legacyAoSteps` must be a whole number from 1 to 64, not 2.5");
  EXPECT_EQ(applySettingsJson(base, {{"shadowMapSize", 8192}}).shadowMapSize, 8192u);
  EXPECT_EQ(applySettingsJson(base, {{"rtPretraceSteps", 256}}).rtPretraceSteps, 256u);
}

// The material override mode goes by name; any other value is refused with the three names.
TEST(SettingsJson, MaterialModeByName) {
  lighting::RenderSettings base;
  EXPECT_EQ(base.materials, lighting::MaterialMode::Authored);
  EXPECT_EQ(applySettingsJson(base, {{"materials", "clay"}}).materials, lighting::MaterialMode::Clay);
  EXPECT_EQ(applySettingsJson(base, {{"materials", "diffuse"}}).materials, lighting::MaterialMode::Diffuse);
  EXPECT_EQ(applySettingsJson(base, {{"materials", "authored"}}).materials, lighting::MaterialMode::Authored);
  for (const nlohmann::json& bad : {nlohmann::json("Clay"), nlohmann::json(2), nlohmann::json("")}) {
    try {
      applySettingsJson(base, {{"materials", bad}});
      FAIL() << "accepted " << bad.dump();
    } catch (const SessionError& e) {
      EXPECT_NE(std::string(e.what()).find("`materials` must be \"authored\", \"diffuse\" or \"clay\""), std::string::npos)
          << e.what();
    }
  }
}

// What a capture manifest records is every setting by name with its value: applied to default
// settings it gives the recorded settings back.
TEST(SettingsJson, EverySettingRoundTrips) {
  lighting::RenderSettings changed;
  changed.width = 320, changed.height = 200;
  changed.rtDenoise = !changed.rtDenoise;
  changed.legacyAoSteps = 7;
  changed.rtFireflyClamp = 12.5f;
  nlohmann::json all = settingsJson(changed);
  EXPECT_EQ(all["width"], 320);
  EXPECT_EQ(all["rtDenoise"], changed.rtDenoise);
  EXPECT_EQ(all["legacyAoSteps"], 7);
  EXPECT_GT(all.size(), 40u) << "every setting, not a few";
  all.erase("width"), all.erase("height");
  const lighting::RenderSettings back = applySettingsJson(lighting::RenderSettings{}, all);
  nlohmann::json again = settingsJson(back);
  again.erase("width"), again.erase("height");
  EXPECT_EQ(again, all);
}

}  // namespace
}  // namespace tl::session

namespace tl::session {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const SessionError& e) {
    return e.what();
  }
  return "(accepted)";
}

// Ranges are checked after conversion to the stored type: one clear error naming the setting,
// what it takes and the value refused, and nothing applied.
TEST(SettingsSchema, ValuesOutsideTheRangeAreRefusedByName) {
  const lighting::RenderSettings base;
  EXPECT_EQ(errorOf([&] { applySettingsJson(base, {{"shadowMapSize", 100000}}); }),
            "setting `shadowMapSize` must be a whole number from 64 to 8192, not 100000");
  EXPECT_EQ(errorOf([&] { applySettingsJson(base, {{"legacyVoxelResolution", 100}}); }),
            "setting `legacyVoxelResolution` must be a whole number from 8 to 256, a power of two, not 100");
  EXPECT_NE(errorOf([&] { applySettingsJson(base, {{"legacyAoSteps", 2.5}}); }).find("a whole number"), std::string::npos);
  EXPECT_NE(errorOf([&] { applySettingsJson(base, {{"rtThickness", -0.001}}); }).find("from 0 to 1"), std::string::npos);
  EXPECT_NE(errorOf([&] { applySettingsJson(base, {{"taaBlend", 0}}); }).find("`taaBlend`"), std::string::npos);
  // 1 + 1e-9 is 1 once stored as a float: within [0.01, 1].
  EXPECT_FLOAT_EQ(applySettingsJson(base, {{"taaBlend", 1.000000001}}).taaBlend, 1.0f);
  // A refused key leaves the others unapplied (the caller keeps `base`).
  EXPECT_THROW(applySettingsJson(base, {{"rtDenoise", false}, {"shadowMapSize", 1}}), SessionError);
  EXPECT_EQ(applySettingsJson(base, {{"shadowMapSize", 4096}}).shadowMapSize, 4096u);
}

TEST(SettingsSchema, TextAssignmentsParseIntoTheStoredType) {
  const lighting::RenderSettings base;
  EXPECT_EQ(applySettingText(base, "shadowMapSize=4096").shadowMapSize, 4096u);
  EXPECT_EQ(applySettingText(base, "materials=clay").materials, lighting::MaterialMode::Clay);
  EXPECT_FALSE(applySettingText(base, "rtDenoise=false").rtDenoise);
  EXPECT_FLOAT_EQ(applySettingText(base, "rtAoRadius=0.5").rtAoRadius, 0.5f);
  EXPECT_EQ(errorOf([&] { applySettingText(base, "shadowMapSize=100000"); }),
            "setting `shadowMapSize` must be a whole number from 64 to 8192, not `100000`");
  EXPECT_NE(errorOf([&] { applySettingText(base, "rtDenoise=yes"); }).find("true or false"), std::string::npos);
  EXPECT_NE(errorOf([&] { applySettingText(base, "rtAoRadius=0.5m"); }).find("a number from"), std::string::npos);
  EXPECT_NE(errorOf([&] { applySettingText(base, "rtBogus=1"); }).find("unknown setting `rtBogus`"), std::string::npos);
  EXPECT_NE(errorOf([&] { applySettingText(base, "rtDenoise"); }).find("NAME=VALUE"), std::string::npos);
}

// Every default lies in its own range, so every settings file Twinlight writes reads back.
TEST(SettingsSchema, DefaultsAreValidAndFormatBackToThemselves) {
  const lighting::RenderSettings defaults;
  EXPECT_GE(lighting::settingsSchema().size(), 57u);  // every RenderSettings field
  for (const auto& s : lighting::settingsSchema()) {
    EXPECT_EQ(s.get(defaults), s.defaultValue) << s.name;
    EXPECT_FALSE(lighting::settingRangeError(s, s.defaultValue)) << s.name << " default " << s.defaultValue;
    EXPECT_EQ(lighting::parseSetting(s, lighting::formatSetting(s, s.defaultValue)), s.defaultValue) << s.name;
    EXPECT_FALSE(s.help.empty()) << s.name;
  }
}

// Every setting belongs to `common` or to a lighting path that exists (the engine's groups name
// their owner once, in TL_RENDER_SETTINGS), and each engine owner's settings are one run of the
// schema: a group is declared in one place.
TEST(SettingsSchema, EachSettingsOwnerIsCommonOrAPathAndItsGroupIsOneRun) {
  std::vector<std::string> paths;
  for (auto make : lighting::lightingPathRegistry()) paths.push_back(make()->name());
  std::vector<std::string_view> runs;
  for (const auto& s : lighting::settingsSchema()) {
    EXPECT_TRUE(s.owner == "common" || std::find(paths.begin(), paths.end(), s.owner) != paths.end())
        << s.name << " is owned by `" << s.owner << "`, neither common nor a path";
    if (runs.empty() || runs.back() != s.owner) runs.push_back(s.owner);
  }
  for (std::string_view owner : runs)
    EXPECT_EQ(std::count(runs.begin(), runs.end(), owner), 1) << "the settings of `" << owner << "` are split";
  EXPECT_EQ(runs.front(), "common");
}

// The history flags name lighting paths that exist, and a path's history settings hash is
// exactly what its flags say: the frame key's `settings` part (docs/design/frame-key.md).
TEST(SettingsSchema, HistoryFlagsDecideEachPathsHistorySettings) {
  std::vector<std::string> paths;
  for (auto make : lighting::lightingPathRegistry()) paths.push_back(make()->name());
  for (const auto& s : lighting::settingsSchema()) {
    std::string_view rest = s.history;
    while (!rest.empty()) {
      const std::string_view word = rest.substr(0, rest.find(' '));
      rest = word.size() == rest.size() ? std::string_view() : rest.substr(word.size() + 1);
      EXPECT_NE(std::find(paths.begin(), paths.end(), word), paths.end()) << s.name << " names a path that does not exist: " << word;
      // An engine setting never names a plugin: the plugin declares what restarts it.
      EXPECT_TRUE(s.owner == word || !lighting::isPluginPath(word)) << s.name << " names the plugin " << word;
    }
  }
  const lighting::RenderSettings base;
  for (const auto& path : paths) {
    for (const auto& s : lighting::settingsSchema()) {
      lighting::RenderSettings changed = base;
      const double other = s.get(base) == s.max ? s.min : (s.type == lighting::SettingType::Float ? s.max : s.get(base) + 1);
      const double v = (s.flags & lighting::kSettingPow2) ? (s.get(base) == s.max ? s.get(base) / 2 : s.get(base) * 2) : other;
      s.set(changed, v);
      EXPECT_EQ(lighting::historySettingsHash(changed, path) != lighting::historySettingsHash(base, path),
                s.resetsHistoryOf(path))
          << s.name << " for " << path;
    }
  }
  // What the docs' frame-key table states.
  auto resets = [](const char* name, const char* path) { return lighting::findSetting(name)->resetsHistoryOf(path); };
  EXPECT_TRUE(resets("materials", "reference") && resets("materials", "rt") && resets("materials", "legacy"));
  EXPECT_TRUE(resets("rtAoRadius", "reference"));
  EXPECT_FALSE(resets("rtMaxAccumFrames", "rt") || resets("rtDenoise", "rt") || resets("rtLumaRejection", "rt") ||
               resets("rtDisocclusionRays", "rt") || resets("rtHalfRays", "rt"));
  EXPECT_FALSE(resets("legacyConeStep", "legacy") || resets("legacyPartialVoxels", "legacy"));
  // The direct path's one history is the light table's accumulation (lights.direct), which
  // depends on the surfaces it shades and on the light shadow maps, not on the rest.
  EXPECT_TRUE(resets("materials", "direct") && resets("lightShadowMapSize", "direct") && resets("lightShadowMaxLights", "direct"));
  EXPECT_FALSE(resets("shadowMapSize", "direct") || resets("rtDenoise", "direct") || resets("legacyConeStep", "direct"));
}

// A plugin's settings are declared in its folder (plugins/bent_sky/) and are in the one schema:
// JSON and `--set` with the range checks, the default where never set, its history; the engine
// settings the plugin's history depends on are declared by the plugin, not named by the engine.
TEST(SettingsSchema, PluginSettingsJoinTheSchemaFromTheirOwnFolder) {
  const lighting::SettingInfo* rays = lighting::findSetting("bentSkyRays");
  ASSERT_NE(rays, nullptr);
  EXPECT_EQ(rays->owner, "bentsky");
  EXPECT_TRUE(lighting::isPluginPath(rays->owner));
  const lighting::RenderSettings base;
  EXPECT_EQ(rays->get(base), 4.0) << "the default, never set";
  const lighting::RenderSettings set = applySettingText(base, "bentSkyRays=16");
  EXPECT_EQ(rays->get(set), 16.0);
  EXPECT_EQ(rays->get(applySettingsJson(base, {{"bentSkyMaxFrames", 8}})), 4.0) << "settings keep their own slots";
  EXPECT_EQ(lighting::findSetting("bentSkyMaxFrames")->get(applySettingsJson(base, {{"bentSkyMaxFrames", 8}})), 8.0);
  EXPECT_THROW(applySettingText(base, "bentSkyRays=0"), SessionError) << "the range it declared";
  EXPECT_THROW(applySettingText(base, "bentSkyRays=2.5"), SessionError);
  EXPECT_NE(lighting::historySettingsHash(set, "bentsky"), lighting::historySettingsHash(base, "bentsky"));
  EXPECT_EQ(lighting::historySettingsHash(set, "rt"), lighting::historySettingsHash(base, "rt"));
  // Declared by the plugin: the materials and the ray length restart its history.
  EXPECT_TRUE(lighting::findSetting("materials")->resetsHistoryOf("bentsky"));
  EXPECT_TRUE(lighting::findSetting("rtRayLength")->resetsHistoryOf("bentsky"));
  EXPECT_FALSE(lighting::findSetting("rtDenoise")->resetsHistoryOf("bentsky"));
  // The plugins' settings follow the engine's, in the order of their owners' names.
  const auto& schema = lighting::settingsSchema();
  const auto firstPlugin = std::find_if(schema.begin(), schema.end(), [](const auto& s) { return lighting::isPluginPath(s.owner); });
  EXPECT_TRUE(std::all_of(firstPlugin, schema.end(), [](const auto& s) { return lighting::isPluginPath(s.owner); }));
  EXPECT_TRUE(std::is_sorted(firstPlugin, schema.end(), [](const auto& a, const auto& b) { return a.owner < b.owner; }));
}

// A setting registered once the schema is in use would be missing from everything made
// before: refused loudly, and the schema is left as it was.
TEST(SettingsSchema, LateRegistrationIsRefused) {
  const size_t before = lighting::settingsSchema().size();
  lighting::SettingInfo late{"lateSetting", lighting::SettingType::UInt, 1, 0, 4, "", "bentsky", "", lighting::kSettingPlain, "late"};
  EXPECT_THROW(lighting::registerPluginSetting(late), std::logic_error);
  EXPECT_THROW(lighting::registerHistoryInputs("bentsky", {"materials"}), std::logic_error);
  EXPECT_EQ(lighting::settingsSchema().size(), before);
  EXPECT_EQ(lighting::findSetting("lateSetting"), nullptr);
}

// docs/user-guide.md holds the settings reference `twinlight settings --markdown` prints.
TEST(SettingsSchema, UserGuideReferenceMatchesTheSchema) {
  const std::filesystem::path guide = std::filesystem::path(TWINLIGHT_CONTENT_DIR) / ".." / "docs" / "user-guide.md";
  std::ifstream in(guide);
  ASSERT_TRUE(in) << guide;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t begin = text.find(kSettingsDocBegin), end = text.find(kSettingsDocEnd);
  ASSERT_NE(begin, std::string::npos) << "no settings reference in " << guide;
  ASSERT_NE(end, std::string::npos);
  const size_t from = text.find('\n', begin) + 1;
  EXPECT_EQ(text.substr(from, end - from), settingsReferenceMarkdown())
      << "regenerate it: twinlight settings --markdown (between the markers in docs/user-guide.md)";
}

}  // namespace
}  // namespace tl::session
