// Render settings from JSON: known keys apply, unknown keys and wrong types are one clear error.
#include "session/session.h"
#include "session/settings_json.h"

#include <fmt/format.h>
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

// Issue 22: values are range-checked before they are converted (shadowMapSize 0 or 65536 gave
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
  EXPECT_EQ(message({{"rtAoRadius", 1e39}}), "setting `rtAoRadius` must be a number from 0 to 1e+06, not 1e+39");
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
