// The editor's undo history of render settings and lighting (session/edit_history.h): steps
// by schema entry, drags folded, undo touching only what a step changed.
#include "session/edit_history.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace tl::session {
namespace {

using scene::Light;

TEST(EditHistory, EverySchemaEntryUndoesAndRedoes) {
  lighting::RenderSettings s;
  Lighting l;
  EditHistory h;
  h.reset(s, l);
  EXPECT_FALSE(h.observe(s, l, false)) << "nothing changed";
  // Each panel setting of the schema, changed to another valid value, is one undoable step.
  size_t checked = 0;
  for (const lighting::SettingInfo& info : lighting::settingsSchema()) {
    if (info.flags & lighting::kSettingNoPanel) continue;
    const double before = info.get(s);
    info.set(s, before == info.max ? info.min : info.max);
    const double after = info.get(s);  // as stored (a float setting rounds)
    ASSERT_TRUE(h.observe(s, l, false)) << info.name;
    EXPECT_NE(h.undoLabel().find(std::string(info.name)), std::string::npos) << h.undoLabel();
    ASSERT_TRUE(h.undo(s, l));
    EXPECT_EQ(info.get(s), before) << info.name;
    ASSERT_TRUE(h.redo(s, l));
    EXPECT_EQ(info.get(s), after) << info.name;
    ASSERT_TRUE(h.undo(s, l));
    ++checked;
  }
  EXPECT_GT(checked, 40u);
  EXPECT_FALSE(h.observe(s, l, false)) << "an undo is not a new edit";
}

TEST(EditHistory, ADragIsOneStepAndUndoLeavesOtherEntriesAlone) {
  lighting::RenderSettings s;
  Lighting l;
  EditHistory h;
  h.reset(s, l);
  s.taaBlend = 0.2f;
  h.observe(s, l, false);
  s.taaBlend = 0.3f;
  h.observe(s, l, true);  // the same drag
  s.taaBlend = 0.4f;
  h.observe(s, l, true);
  EXPECT_EQ(h.steps(), 1u);
  s.shadowMapSize = 512;
  h.observe(s, l, true);  // another entry: a new step even while "continuing"
  EXPECT_EQ(h.steps(), 2u);
  s.width = 1234;  // the viewport resized: not an edit
  EXPECT_FALSE(h.observe(s, l, false));
  ASSERT_TRUE(h.undo(s, l));
  EXPECT_EQ(s.shadowMapSize, 2048u);
  EXPECT_FLOAT_EQ(s.taaBlend, 0.4f);
  ASSERT_TRUE(h.undo(s, l));
  EXPECT_FLOAT_EQ(s.taaBlend, lighting::RenderSettings{}.taaBlend) << "the drag as a whole";
  EXPECT_EQ(s.width, 1234u) << "the image size is the viewport's";
  EXPECT_FALSE(h.canUndo());
  ASSERT_TRUE(h.redo(s, l));
  EXPECT_FLOAT_EQ(s.taaBlend, 0.4f);
  s.softShadows = false;
  h.observe(s, l, false);
  EXPECT_FALSE(h.canRedo()) << "a new edit drops the redo history";
}

TEST(EditHistory, LightingIsUndoneWithTheSettings) {
  lighting::RenderSettings s;
  Lighting l;
  EditHistory h;
  h.reset(s, l);
  const Lighting before = l;
  l.sunIrradiance = glm::vec3(3.0f);
  l.exposureEv = 2.0f;
  s.taa = true;
  ASSERT_TRUE(h.observe(s, l, false));
  EXPECT_NE(h.undoLabel().find("lighting"), std::string::npos);
  ASSERT_TRUE(h.undo(s, l));
  EXPECT_TRUE(sameLighting(l, before));
  EXPECT_FALSE(s.taa);
  ASSERT_TRUE(h.redo(s, l));
  EXPECT_EQ(l.sunIrradiance, glm::vec3(3.0f));
  EXPECT_TRUE(s.taa);
}

// A history that was never given a state to watch from (an editor that opened its first scene
// before any reset) takes the first state it sees as that state: the scene's loaded lights are
// not an edit, so the first undo after start-up finds nothing (it used to take the lamps' three
// lights and the atrium's sun away, and a save then deleted them from the file).
TEST(EditHistory, TheFirstStateSeenIsWhereTheHistoryStartsNotAnEdit) {
  lighting::RenderSettings s;
  s.shadowMapSize = 512;
  Lighting loaded;
  loaded.sunIrradiance = glm::vec3(20.0f);
  loaded.lights.resize(3);
  loaded.lights[0].name = "bulb";
  EditHistory h;
  EXPECT_FALSE(h.observe(s, loaded, false));
  EXPECT_FALSE(h.canUndo());
  EXPECT_EQ(h.steps(), 0u);
  EXPECT_EQ(h.undoLabel(), "");
  Lighting l = loaded;
  EXPECT_FALSE(h.undo(s, l));
  EXPECT_TRUE(sameLighting(l, loaded));
  EXPECT_EQ(s.shadowMapSize, 512u);
  // From there on every change is an edit, and undoing it goes back to the loaded state.
  l.lights.pop_back();
  ASSERT_TRUE(h.observe(s, l, false));
  ASSERT_TRUE(h.undo(s, l));
  EXPECT_TRUE(sameLighting(l, loaded));
  EXPECT_FALSE(h.canUndo());
}

// A scene reloaded reads its environment map again: the artist's lighting kept across the reload
// holds the copy read before. The same file with the same texels is the same lighting (a light
// added and deleted again left the scene "unsaved" forever, found by the editor soak walk on
// courtyard); another file, or the same file with other texels, is not.
TEST(EditHistory, AnEnvironmentMapReadAgainIsTheSameLighting) {
  auto read = [](const char* path, float value) {
    scene::EnvironmentMap m = scene::makeEnvironmentMap(4, 2, std::vector<glm::vec3>(8, glm::vec3(value)));
    m.path = path;
    return std::make_shared<const scene::EnvironmentMap>(std::move(m));
  };
  Lighting before, reloaded, otherFile, otherTexels;
  before.environmentMap = read("sky.exr", 1.0f);
  reloaded.environmentMap = read("sky.exr", 1.0f);
  otherFile.environmentMap = read("dusk.exr", 1.0f);
  otherTexels.environmentMap = read("sky.exr", 2.0f);
  ASSERT_NE(before.environmentMap, reloaded.environmentMap);
  EXPECT_TRUE(sameLighting(before, reloaded));
  EXPECT_FALSE(sameLighting(before, otherFile));
  EXPECT_FALSE(sameLighting(before, otherTexels));
  EXPECT_FALSE(sameLighting(before, Lighting{})) << "a map against none";

  EditHistory h;
  h.reset(lighting::RenderSettings{}, before);
  EXPECT_FALSE(h.observe(lighting::RenderSettings{}, reloaded, false)) << "reading the map again is not an edit";
  EXPECT_TRUE(h.observe(lighting::RenderSettings{}, otherTexels, false));
}

// The same light to an artist: what the kind casts, within float rounding; the node it is saved
// to and a point light's unused direction are not edits, so a light added again where a saved
// one stood is no unsaved work (the editor soak found the editor asking after a file read back).
TEST(EditHistory, ALightIsComparedByWhatItsKindCasts) {
  Light point;
  point.type = scene::LightType::Point;
  point.name = "point 1";
  point.position = {0.0, 1.0, 2.8607696294784546};
  point.intensity = 40.5f;
  Light readBack = point;
  readBack.node = 9;
  readBack.direction = {0.0, 0.0, -1.0};
  point.direction = {0.0, -1.0, 0.0};
  EXPECT_TRUE(sameLight(point, readBack)) << "a point light's direction and node are not edits";
  readBack.position.z += 1e-3;
  EXPECT_FALSE(sameLight(point, readBack)) << "a millimetre's move is an edit";

  Light spot = point;
  spot.type = scene::LightType::Spot;
  Light rounded = spot;
  rounded.direction = glm::normalize(glm::dvec3(1e-9, -1.0, 2e-9));  // a node's rotation, read back
  EXPECT_TRUE(sameLight(spot, rounded));
  rounded.direction = glm::normalize(glm::dvec3(0.0, -1.0, 1e-3));
  EXPECT_FALSE(sameLight(spot, rounded)) << "a spot turned";
  Light wider = spot;
  wider.outerConeAngle += 0.01f;
  EXPECT_FALSE(sameLight(spot, wider));
  Light brighter = point;
  brighter.intensity *= 1.001f;
  EXPECT_FALSE(sameLight(point, brighter));
  Light rect = point;
  rect.type = scene::LightType::Rect;
  Light taller = rect;
  taller.height = 2.0f;
  EXPECT_FALSE(sameLight(rect, taller));
  taller = rect;
  taller.radius = 3.0f;  // a rectangle has no radius
  EXPECT_TRUE(sameLight(rect, taller));
}

}  // namespace
}  // namespace tl::session
