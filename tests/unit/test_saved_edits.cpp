// Undo holds only the artist's edits and saving keeps what the artist did not remove: seeded
// random walks of edits on content/lamps.gltf, saved after undo and redo and the scene opened again
// as the editor opens it (session/lighting_file.h openingLighting). What opens is what the walk says
// the artist has, and the glTF alone holds every shown light of it (other tools read that file).
// The second walk takes all three kinds of work File > Save writes: the lighting, the render
// settings saved with the scene and the albedo overrides in the scene's database, undone across
// the editor's two histories as its Ctrl+Z and Ctrl+Y do.
#include "../common/temp_dir.h"
#include "albedo/albedo_library.h"
#include "scene/scene.h"
#include "session/edit_history.h"
#include "session/lighting_file.h"
#include "session/settings_json.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <random>

namespace tl::session {
namespace {

namespace fs = std::filesystem;
using scene::Light;
using scene::LightType;

// What the artist has: the lighting and the settings the walk changes.
struct ArtistState {
  Lighting lighting;
  lighting::RenderSettings settings;
};

// Equal as a file holds them: positions and colours exactly (written as JSON numbers that read
// back to the same double or float), directions to the rounding of a normalisation.
std::string lightDifference(const Light& want, const Light& got) {
  if (want.name != got.name) return fmt::format("name `{}` != `{}`", want.name, got.name);
  if (want.type != got.type) return "type";
  if (want.color != got.color) return "colour";
  if (want.intensity != got.intensity) return fmt::format("intensity {} != {}", want.intensity, got.intensity);
  if (want.hidden != got.hidden) return "hidden";
  if (want.type != LightType::Directional && want.position != got.position) return "position";
  if (want.type != LightType::Point && glm::dot(glm::normalize(want.direction), got.direction) < 1.0 - 1e-12) return "direction";
  if (want.type == LightType::Spot &&
      (std::abs(want.innerConeAngle - got.innerConeAngle) > 1e-6f || std::abs(want.outerConeAngle - got.outerConeAngle) > 1e-6f))
    return "cone";
  return {};
}

std::string lightingDifference(const Lighting& want, const Lighting& got) {
  if (want.sunIrradiance != got.sunIrradiance) return "sun irradiance";
  if (glm::dot(glm::normalize(want.sunDirection), got.sunDirection) < 1.0 - 1e-12) return "sun direction";
  if (want.skyRadiance != got.skyRadiance) return "sky radiance";
  if (want.exposureEv.has_value() != got.exposureEv.has_value() ||
      (want.exposureEv && std::abs(*want.exposureEv - *got.exposureEv) > 1e-6f))
    return "exposure";
  if (want.lights.size() != got.lights.size())
    return fmt::format("{} lights, {} expected", got.lights.size(), want.lights.size());
  for (size_t i = 0; i < want.lights.size(); ++i)
    if (std::string d = lightDifference(want.lights[i], got.lights[i]); !d.empty()) return fmt::format("light {}: {}", i, d);
  return {};
}

// One edit an artist makes in the editor: a light added (in front of the camera), deleted,
// moved, brightened, recoloured, hidden or shown, the sun or the sky changed, exposure set, or a
// render setting changed.
void editOnce(ArtistState& a, std::mt19937& rng, int& added) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
  Lighting& l = a.lighting;
  switch (pick(9)) {
    case 0:
    case 1: {
      Light n;
      const LightType types[] = {LightType::Point, LightType::Spot, LightType::Rect, LightType::Directional};
      n.type = types[pick(4)];
      n.name = fmt::format("{} {}", scene::lightTypeName(n.type), ++added);
      n.position = {uniform(-2, 2), uniform(0.5, 2.5), uniform(-2, 2)};
      n.direction = glm::normalize(glm::dvec3(uniform(-1, 1), -1.0, uniform(-1, 1)));
      n.intensity = float(uniform(10, 500));
      if (n.type == LightType::Spot) n.innerConeAngle = 0.3f, n.outerConeAngle = 0.5f;
      l.lights.push_back(n);
      break;
    }
    case 2:
      if (!l.lights.empty()) l.lights.erase(l.lights.begin() + std::ptrdiff_t(pick(l.lights.size())));
      break;
    case 3:
      if (!l.lights.empty()) l.lights[pick(l.lights.size())].position += glm::dvec3(uniform(-0.5, 0.5), 0.0, uniform(-0.5, 0.5));
      break;
    case 4:
      if (!l.lights.empty()) l.lights[pick(l.lights.size())].intensity = float(uniform(1, 900));
      break;
    case 5:
      if (!l.lights.empty()) {
        Light& x = l.lights[pick(l.lights.size())];
        x.hidden = !x.hidden;
        x.color = glm::vec3(float(uniform(0.2, 1)), float(uniform(0.2, 1)), 1.0f);
      }
      break;
    case 6:
      l.sunIrradiance = pick(4) == 0 ? glm::vec3(0.0f) : glm::vec3(float(uniform(1, 40)));
      l.sunDirection = glm::normalize(glm::dvec3(uniform(-1, 1), -1.0, uniform(-1, 1)));
      break;
    case 7:
      l.skyRadiance = glm::vec3(float(uniform(0.0, 2.0)));
      l.exposureEv = pick(2) ? std::optional<float>(float(uniform(-2, 4))) : std::nullopt;
      break;
    default:
      a.settings.shadowMapSize = a.settings.shadowMapSize == 1024 ? 2048 : 1024;
      break;
  }
}

class SavedEditsTest : public ::testing::Test {
 protected:
  test::TempDir scratch;
  fs::path copyOf(const std::string& name) {
    fs::copy_file(test::contentFile(name.c_str()), scratch.path / name);
    fs::path bin = fs::path(name).replace_extension(".bin");
    fs::copy_file(test::contentFile(bin.string().c_str()), scratch.path / bin);
    return scratch.path / name;
  }
};

TEST_F(SavedEditsTest, ARandomWalkOfEditsUndoneRedoneAndSavedOpensAsTheArtistLeftIt) {
  const fs::path file = copyOf("lamps.gltf");
  const OpeningLighting first = openingLighting(scene::loadGltf(file), std::nullopt, true);
  ASSERT_TRUE(first.error.empty()) << first.error;
  ASSERT_EQ(first.lighting.lights.size(), 3u);

  ArtistState now{first.lighting, {}};
  EditHistory history;
  history.reset(now.settings, now.lighting);
  // The states an undo and a redo step through: made[0] is the scene as it opened.
  std::vector<ArtistState> made{now};
  size_t at = 0;
  std::mt19937 rng(20240611);
  int added = 0, saves = 0, undos = 0, redos = 0;
  constexpr int kActions = 200;
  for (int action = 0; action < kActions; ++action) {
    SCOPED_TRACE(fmt::format("action {}", action));
    const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
    bool stepped = false;
    if (kind < 5) {
      editOnce(now, rng, added);
      if (!history.observe(now.settings, now.lighting, false)) continue;  // an edit that changed nothing
      made.resize(at + 1);
      made.push_back(now);
      ++at;
    } else if (kind < 8) {
      const bool did = history.undo(now.settings, now.lighting);
      ASSERT_EQ(did, at > 0) << "an undo with " << at << " edits to undo";
      if (did) --at, ++undos;
      stepped = true;
    } else {
      const bool did = history.redo(now.settings, now.lighting);
      ASSERT_EQ(did, at + 1 < made.size());
      if (did) ++at, ++redos;
      stepped = true;
    }
    ASSERT_EQ(lightingDifference(made[at].lighting, now.lighting), "");
    ASSERT_EQ(now.settings.shadowMapSize, made[at].settings.shadowMapSize);
    if (!stepped) continue;

    // File > Save lighting, then the scene opened again.
    saveSceneLighting(file, now.lighting);
    ++saves;
    EXPECT_FALSE(history.observe(now.settings, now.lighting, false)) << "saving (the lights' new nodes) is not an edit";
    const scene::Scene reloaded = scene::loadGltf(file);
    const OpeningLighting opened = openingLighting(reloaded, std::nullopt, true);
    ASSERT_TRUE(opened.error.empty()) << opened.error;
    ASSERT_EQ(lightingDifference(now.lighting, opened.lighting), "");
    // The glTF alone: the sun (when it shines) and every shown punctual light, nothing else.
    std::vector<std::string> want, got;
    for (const Light& x : now.lighting.lights)
      if (!x.hidden && !scene::isAreaLight(x.type)) want.push_back(x.name);
    for (size_t i = 0; i < reloaded.lights.size(); ++i)
      if (i != reloaded.environment.sunLight || glm::length(now.lighting.sunIrradiance) == 0.0f)
        got.push_back(reloaded.lights[i].name);
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    ASSERT_EQ(want, got);
    ASSERT_EQ(reloaded.environment.sunFromFile && reloaded.environment.sunLight &&
                  reloaded.lights[*reloaded.environment.sunLight].name == (now.lighting.sunName.empty() ? "Sun" : now.lighting.sunName),
              glm::length(now.lighting.sunIrradiance) > 0.0f);
  }
  // The walk did what it is for.
  EXPECT_GT(saves, 60);
  EXPECT_GT(undos, 30);
  EXPECT_GT(redos, 10);
  EXPECT_GT(added, 10);
  // Saving after undo and redo reuses the lights' nodes where it can: the file does not grow a
  // node per save.
  const auto doc = nlohmann::json::parse(std::ifstream(file));
  const size_t before = nlohmann::json::parse(std::ifstream(test::contentFile("lamps.gltf")))["nodes"].size();
  EXPECT_LE(doc["nodes"].size(), before + size_t(added) + 1) << saves << " saves";
}


// The editor's Ctrl+Z and Ctrl+Y (editor/editor_app.cpp EditorApp::undo and redo) over its two
// histories: the latest edit of either is undone first, and redo goes forward from the earliest.
bool undoLatest(EditHistory& history, albedo::AlbedoLibrary& albedo, ArtistState& now) {
  const auto settingsAt = history.undoTime(), albedoAt = albedo.undoTime();
  if (albedoAt && (!settingsAt || *albedoAt > *settingsAt)) return albedo.undo();
  return history.undo(now.settings, now.lighting);
}
bool redoEarliest(EditHistory& history, albedo::AlbedoLibrary& albedo, ArtistState& now) {
  const auto settingsAt = history.redoTime(), albedoAt = albedo.redoTime();
  if (albedoAt && (!settingsAt || *albedoAt < *settingsAt)) return albedo.redo();
  return history.redo(now.settings, now.lighting);
}

// What the walk says one history holds: the states it steps through (states[0] as the scene
// opened), `at` applied, and when each step was made (the walk's own count of edits).
template <typename State>
struct ModelHistory {
  std::vector<State> states;
  std::vector<int> madeAt;  // madeAt[i]: the edit that made states[i + 1]
  size_t at = 0;
  void push(const State& s, int when) {
    states.resize(at + 1);
    madeAt.resize(at);
    states.push_back(s);
    madeAt.push_back(when);
    ++at;
  }
  std::optional<int> undoAt() const { return at > 0 ? std::optional(madeAt[at - 1]) : std::nullopt; }
  std::optional<int> redoAt() const { return at + 1 < states.size() ? std::optional(madeAt[at]) : std::nullopt; }
};

using Overrides = std::map<uint32_t, glm::vec3>;  // combination -> the artist's colour

Overrides overridesOf(const albedo::AlbedoLibrary& lib) {
  Overrides o;
  for (uint32_t c = 0; c < lib.entries().size(); ++c)
    if (lib.entries()[c].override) o[c] = *lib.entries()[c].override;
  return o;
}

// The settings saved with a scene, as the editor keeps them (settings.json's sceneSettings: the
// panel's settings as JSON, written and read again as text) and applies when it opens the scene.
lighting::RenderSettings savedAndReadSettings(const lighting::RenderSettings& settings, const fs::path& file) {
  std::ofstream(file) << settingsJson(settings).dump(2);
  return applySettingsJson(lighting::RenderSettings{}, nlohmann::json::parse(std::ifstream(file)));
}

TEST_F(SavedEditsTest, TwoHundredEditsOfLightsSettingsAndOverridesSavedAfterEachUndoAndRedoSequenceOpenAsTheArtistLeftThem) {
  const fs::path file = copyOf("lamps.gltf");
  const fs::path dbFile = scratch.path / "lamps.albedo.db";
  const fs::path settingsFile = scratch.path / "scene_settings.json";
  const scene::Scene opened = scene::loadGltf(file);
  const OpeningLighting first = openingLighting(opened, std::nullopt, true);
  ASSERT_TRUE(first.error.empty()) << first.error;
  albedo::AlbedoLibrary albedo(opened);
  albedo.attach(std::make_unique<albedo::AlbedoDatabase>(dbFile));
  const uint32_t combinations = uint32_t(albedo.entries().size());
  ASSERT_GE(combinations, 3u);

  ArtistState now{first.lighting, {}};
  EditHistory history;
  history.reset(now.settings, now.lighting);
  ModelHistory<ArtistState> lightingModel{{now}, {}, 0};
  ModelHistory<Overrides> albedoModel{{{}}, {}, 0};
  std::mt19937 rng(20261205);
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  int edits = 0, added = 0, overrides = 0, sequences = 0, undos = 0, redos = 0, albedoSteps = 0;
  constexpr int kEdits = 200;
  while (edits < kEdits) {
    SCOPED_TRACE(fmt::format("edit {}", edits));
    if (pick(10) < 6) {
      // An edit: a third of them an albedo override, the rest lights, the sun, sky and settings.
      if (pick(3) == 0) {
        const uint32_t c = uint32_t(pick(int(combinations)));
        const glm::vec3 rgb(float(pick(1000)) / 1000.0f, float(pick(1000)) / 1000.0f, float(pick(1000)) / 1000.0f);
        if (albedo.entries()[c].override == rgb) continue;
        albedo.setOverride(c, rgb);
        albedoModel.push(overridesOf(albedo), ++edits);
        ++overrides;
      } else {
        editOnce(now, rng, added);
        if (pick(4) == 0) now.settings.taa = !now.settings.taa;
        if (!history.observe(now.settings, now.lighting, false)) continue;  // an edit that changed nothing
        lightingModel.push(now, ++edits);
      }
      ASSERT_EQ(lightingDifference(lightingModel.states[lightingModel.at].lighting, now.lighting), "");
      ASSERT_EQ(overridesOf(albedo), albedoModel.states[albedoModel.at]);
      continue;
    }
    // A sequence of one to five presses of Ctrl+Z or Ctrl+Y, then File > Save.
    const int presses = 1 + pick(5);
    for (int p = 0; p < presses; ++p) {
      if (pick(3) < 2) {
        const auto l = lightingModel.undoAt(), a = albedoModel.undoAt();
        const bool albedoFirst = a && (!l || *a > *l);
        ASSERT_EQ(undoLatest(history, albedo, now), bool(l || a));
        if (albedoFirst) --albedoModel.at, ++albedoSteps;
        else if (l) --lightingModel.at;
        ++undos;
      } else {
        const auto l = lightingModel.redoAt(), a = albedoModel.redoAt();
        const bool albedoFirst = a && (!l || *a < *l);
        ASSERT_EQ(redoEarliest(history, albedo, now), bool(l || a));
        if (albedoFirst) ++albedoModel.at, ++albedoSteps;
        else if (l) ++lightingModel.at;
        ++redos;
      }
      const ArtistState& want = lightingModel.states[lightingModel.at];
      ASSERT_EQ(lightingDifference(want.lighting, now.lighting), "") << "press " << p;
      ASSERT_EQ(now.settings.shadowMapSize, want.settings.shadowMapSize);
      ASSERT_EQ(now.settings.taa, want.settings.taa);
      ASSERT_EQ(overridesOf(albedo), albedoModel.states[albedoModel.at]);
    }
    ++sequences;
    // File > Save: the lighting into the glTF and its sidecar, the settings with the scene, the
    // overrides into the database. Then the scene opened again from those files alone.
    saveSceneLighting(file, now.lighting);
    EXPECT_FALSE(history.observe(now.settings, now.lighting, false)) << "saving (the lights' new nodes) is not an edit";
    const lighting::RenderSettings settingsRead = savedAndReadSettings(now.settings, settingsFile);
    albedo.save();
    EXPECT_FALSE(albedo.unsaved());

    const scene::Scene reloaded = scene::loadGltf(file);
    const OpeningLighting reopened = openingLighting(reloaded, std::nullopt, true);
    ASSERT_TRUE(reopened.error.empty()) << reopened.error;
    const ArtistState& want = lightingModel.states[lightingModel.at];
    ASSERT_EQ(lightingDifference(want.lighting, reopened.lighting), "");
    ASSERT_EQ(settingsRead.shadowMapSize, want.settings.shadowMapSize);
    ASSERT_EQ(settingsRead.taa, want.settings.taa);
    albedo::AlbedoLibrary reopenedAlbedo(reloaded);
    reopenedAlbedo.attach(std::make_unique<albedo::AlbedoDatabase>(dbFile));
    ASSERT_EQ(overridesOf(reopenedAlbedo), albedoModel.states[albedoModel.at]);
    EXPECT_EQ(reopenedAlbedo.orphanCount(), 0u) << "every override reaches its mesh + material again";
  }
  // The walk did what it is for: every kind of edit, undone and redone across both histories.
  fmt::print("the walk: {} edits ({} overrides, {} lights added), {} undo/redo sequences ({} undos, {} redos, {} of them "
             "albedo steps), each saved and opened again\n", edits, overrides, added, sequences, undos, redos, albedoSteps);
  EXPECT_EQ(edits, kEdits);
  EXPECT_GT(sequences, 60);
  EXPECT_GT(undos, 60);
  EXPECT_GT(redos, 30);
  EXPECT_GT(overrides, 40);
  EXPECT_GT(albedoSteps, 20);
  EXPECT_GT(added, 10);
  EXPECT_GT(lightingModel.states.size(), 2u);
}

}  // namespace
}  // namespace tl::session
