// Point, spot and area light shadow views (lighting/common/light_shadows.h): which lights get maps,
// that every direction from a point light lands inside its face's guarded tile, that a spot's one
// view covers its cone, and that the depth the lookup compares is the one the raster stores.
#include "lighting/common/light_shadows.h"
#include "lighting/common/light_table.h"
#include "shared/lights.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tl::lighting {
namespace {

scene::Light light(scene::LightType type, glm::dvec3 position, float candela) {
  scene::Light l;
  l.type = type;
  l.intensity = candela;
  l.position = position;
  l.direction = {0.0, -1.0, 0.0};
  l.innerConeAngle = 0.2f;
  l.outerConeAngle = 0.5f;
  return l;
}

const glm::dvec3 kMin(-10.0), kMax(10.0);

TEST(LightShadows, PointLightsGetSixViewsSpotsOneAndTheMostPowerfulComeFirst) {
  auto table = buildLightTable({light(scene::LightType::Point, {0, 2, 0}, 100.0f), light(scene::LightType::Spot, {1, 2, 0}, 900.0f),
                                light(scene::LightType::Directional, {0, 0, 0}, 1000.0f)},
                               glm::dvec3(0.0), 10.0);
  ASSERT_EQ(table.size(), 3u);
  const LightShadowPlan plan = planLightShadows(table, 256, 8, kMin, kMax);
  EXPECT_EQ(plan.views.size(), 7u);
  // By power: the point light's 4 pi x 100 cd outweighs the spot's 2 pi (1 - cos 0.5) x 900 cd.
  EXPECT_EQ(table[0].shadowView, 0u);
  EXPECT_EQ(table[1].shadowView, 6u);
  EXPECT_EQ(table[2].shadowView, shared::kNoLightShadow);  // directional: no map
  EXPECT_GE(plan.columns * plan.rows, 7u);
  EXPECT_EQ(plan.atlasWidth(), plan.columns * 256u);
  // Only the most powerful light when one is allowed.
  const LightShadowPlan one = planLightShadows(table, 256, 1, kMin, kMax);
  uint32_t shadowed = 0;
  for (const auto& l : table) shadowed += l.shadowView != shared::kNoLightShadow ? 1u : 0u;
  EXPECT_EQ(shadowed, 1u);
  EXPECT_EQ(table[0].shadowView, 0u);
  EXPECT_FALSE(one.views.empty());
  // None: no views, no atlas.
  const LightShadowPlan none = planLightShadows(table, 256, 0, kMin, kMax);
  EXPECT_TRUE(none.views.empty());
  EXPECT_EQ(none.atlasWidth(), 0u);
  for (const auto& l : table) EXPECT_EQ(l.shadowView, shared::kNoLightShadow);
}

// Where position p lands in view v: uv in [0, 1] of the tile and the clip w.
glm::dvec3 project(const shared::GpuShadowView& v, glm::dvec3 p) {
  const glm::dvec4 clip = glm::dmat4(v.viewProj) * glm::dvec4(p, 1.0);
  return {clip.x / clip.w * 0.5 + 0.5, clip.y / clip.w * 0.5 + 0.5, clip.w};
}

TEST(LightShadows, EveryDirectionFromAPointLightLandsInsideItsFacesGuardedTile) {
  auto table = buildLightTable({light(scene::LightType::Point, {1, 2, 3}, 683.0f)}, glm::dvec3(0.0), 10.0);
  const uint32_t tile = 128;
  const LightShadowPlan plan = planLightShadows(table, tile, 8, kMin, kMax);
  ASSERT_EQ(plan.views.size(), 6u);
  const double guard = shared::kLightShadowGuardTexels / tile;
  double tightest = 1.0;
  for (int i = 0; i < 2000; ++i) {
    // Directions over the sphere (a Fibonacci lattice), 3 m from the light.
    const double z = 1.0 - 2.0 * (i + 0.5) / 2000.0, phi = i * 2.399963229728653;
    const glm::dvec3 d(std::sqrt(1.0 - z * z) * std::cos(phi), z, std::sqrt(1.0 - z * z) * std::sin(phi));
    const uint32_t face = shared::tlCubeFace(glm::vec3(d));
    const glm::dvec3 uvw = project(plan.views[face], glm::dvec3(1, 2, 3) + 3.0 * d);
    tightest = std::min({tightest, uvw.x, uvw.y, 1.0 - uvw.x, 1.0 - uvw.y});
    // The view depth of a point along the face's axis is its distance along that axis.
    EXPECT_NEAR(uvw.z, 3.0 * std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), 1e-4);
  }
  EXPECT_GE(tightest, guard - 1e-4);
  EXPECT_LT(tightest, guard + 0.01);  // and the guard is not much wider than asked
}

TEST(LightShadows, TheCubeFacesProjectionWithoutAMatrixIsTheViews) {
  // tlCubeFaceProject (an area light's soft-shadow taps) against each face's viewProj.
  auto table = buildLightTable({light(scene::LightType::Point, {1, 2, 3}, 683.0f)}, glm::dvec3(0.0), 10.0);
  const uint32_t tile = 128;
  const LightShadowPlan plan = planLightShadows(table, tile, 8, kMin, kMax);
  ASSERT_EQ(plan.views.size(), 6u);
  const double tanHalf = double(plan.views[0].params.z) * tile / 2.0;
  for (int i = 0; i < 500; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / 500.0, phi = i * 2.399963229728653;
    const glm::dvec3 d = 2.5 * glm::dvec3(std::sqrt(1.0 - z * z) * std::cos(phi), z, std::sqrt(1.0 - z * z) * std::sin(phi));
    const uint32_t face = shared::tlCubeFace(glm::vec3(d));
    const glm::dvec3 uvw = project(plan.views[face], glm::dvec3(1, 2, 3) + d);
    const glm::vec3 p = shared::tlCubeFaceProject(face, glm::vec3(d));
    EXPECT_NEAR(p.x / tanHalf * 0.5 + 0.5, uvw.x, 1e-5) << "face " << face;
    EXPECT_NEAR(p.y / tanHalf * 0.5 + 0.5, uvw.y, 1e-5) << "face " << face;
    EXPECT_NEAR(p.z, uvw.z, 1e-5) << "face " << face;
  }
}

TEST(LightShadows, ASpotsViewCoversItsOuterConeAndTheLookupDepthMatchesTheRaster) {
  auto table = buildLightTable({light(scene::LightType::Spot, {0, 2, 0}, 683.0f)}, glm::dvec3(0.0), 10.0);
  const LightShadowPlan plan = planLightShadows(table, 256, 8, kMin, kMax);
  ASSERT_EQ(plan.views.size(), 1u);
  const auto& v = plan.views[0];
  EXPECT_EQ(v.params.w, 1.0f);
  // A point on the outer cone's edge, 2 m down: inside the tile, the guard band outside it.
  const double r = 2.0 * std::tan(0.5);
  const glm::dvec3 uvw = project(v, {r, 0.0, 0.0});
  EXPECT_GT(uvw.x, 0.0);
  EXPECT_LT(uvw.x, 1.0);
  EXPECT_NEAR(std::max(uvw.x, 1.0 - uvw.x), 1.0 - shared::kLightShadowGuardTexels / 256.0, 1e-4);
  // The raster stores clip z / w; the lookup rebuilds it from w (tlShadowViewDepth).
  const glm::dvec4 clip = glm::dmat4(v.viewProj) * glm::dvec4(0.3, 0.0, 0.2, 1.0);
  EXPECT_NEAR(shared::tlShadowViewDepth(v.params.x, v.params.y, float(clip.w)), clip.z / clip.w, 1e-5);
  // The far plane reaches the scene's farthest corner from the light.
  EXPECT_GE(v.params.y, float(glm::length(glm::dvec3(10, -10, 10) - glm::dvec3(0, 2, 0))));
  // A spot wider than kLightShadowMaxSpotTan takes a cube.
  auto wide = light(scene::LightType::Spot, {0, 2, 0}, 683.0f);
  wide.outerConeAngle = 1.3f;
  auto wideTable = buildLightTable({wide}, glm::dvec3(0.0), 10.0);
  EXPECT_EQ(planLightShadows(wideTable, 256, 8, kMin, kMax).views.size(), 6u);
}

TEST(LightShadows, AreaLightsGetACubeFromTheirCentreAndTheDepthInvertsToMetres) {
  scene::Light rect = light(scene::LightType::Rect, {0, 2.5, 1}, 683.0f);
  rect.width = 0.8f;
  rect.height = 0.4f;
  rect.widthAxis = {1.0, 0.0, 0.0};
  auto table = buildLightTable({light(scene::LightType::Directional, {0, 0, 0}, 1000.0f), rect}, glm::dvec3(0.0), 10.0);
  const LightShadowPlan plan = planLightShadows(table, 256, 8, kMin, kMax);
  ASSERT_EQ(plan.views.size(), 6u);
  EXPECT_EQ(table[0].shadowView, shared::kNoLightShadow);
  EXPECT_EQ(table[1].shadowView, 0u);
  EXPECT_EQ(plan.views[0].params.w, 6.0f);
  // The cube sits at the shape's centre: a point 1.5 m straight below lands in the -y face's
  // centre at view depth 1.5 m.
  const glm::dvec3 uvw = project(plan.views[3], {0.0, 1.0, 1.0});
  EXPECT_NEAR(uvw.x, 0.5, 1e-5);
  EXPECT_NEAR(uvw.y, 0.5, 1e-5);
  EXPECT_NEAR(uvw.z, 1.5, 1e-5);
  // The blocker search reads map depths back as metres (tlShadowViewW inverts tlShadowViewDepth).
  const auto& v = plan.views[3];
  for (float w : {0.05f, 0.3f, 1.5f, 7.0f, 20.0f}) {
    const float depth = shared::tlShadowViewDepth(v.params.x, v.params.y, w);
    EXPECT_NEAR(shared::tlShadowViewW(v.params.x, v.params.y, depth) / w, 1.0, 1e-3) << w;
  }
}

TEST(LightShadows, LightsThatDoNotFitTheAtlasGoUnshadowed) {
  std::vector<scene::Light> lights;
  for (int i = 0; i < 8; ++i) lights.push_back(light(scene::LightType::Point, {double(i), 2, 0}, 683.0f));
  auto table = buildLightTable(lights, glm::dvec3(0.0), 10.0);
  // 4096^2 tiles: 16 fit a 16384^2 atlas, two point lights (12 views), not three.
  const LightShadowPlan plan = planLightShadows(table, 4096, 8, kMin, kMax);
  EXPECT_EQ(plan.views.size(), 12u);
  EXPECT_LE(plan.atlasWidth(), kLightShadowAtlasMax);
  EXPECT_LE(plan.atlasHeight(), kLightShadowAtlasMax);
}

}  // namespace
}  // namespace tl::lighting
