// Render settings from JSON: known keys apply, unknown keys and wrong types are one clear error.
#include "session/session.h"
#include "session/settings_json.h"

#include <gtest/gtest.h>

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
