#include "lighting/common/light_shadows.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tl::lighting {

namespace {

// A view from `eye` along `forward` whose square frustum has half-width tanHalf at unit depth.
shared::GpuShadowView makeView(const glm::dvec3& eye, const glm::dvec3& forward, double tanHalf, double farPlane,
                               uint32_t tileTexels, uint32_t viewCount) {
  const glm::dvec3 up = std::abs(forward.y) > 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
  const double nearPlane = double(shared::kLightShadowNearShare) * farPlane;
  const glm::dmat4 view = glm::lookAtRH(eye, eye + forward, up);
  const glm::dmat4 proj = glm::perspectiveRH_ZO(2.0 * std::atan(tanHalf), 1.0, nearPlane, farPlane);
  shared::GpuShadowView v{};
  v.viewProj = glm::mat4(proj * view);
  v.params = glm::vec4(float(nearPlane), float(farPlane), float(2.0 * tanHalf / tileTexels), float(viewCount));
  return v;
}

}  // namespace

LightShadowPlan planLightShadows(std::vector<shared::GpuLight>& table, uint32_t tileTexels, uint32_t maxLights,
                                 const glm::dvec3& sceneMin, const glm::dvec3& sceneMax) {
  LightShadowPlan plan;
  plan.tileTexels = tileTexels;
  for (auto& l : table) l.shadowView = shared::kNoLightShadow;
  if (tileTexels == 0 || maxLights == 0) return plan;

  // Point, spot and area lights, most powerful first (selection probability is power's share).
  std::vector<size_t> order;
  for (size_t i = 0; i < table.size(); ++i)
    if (table[i].type != shared::kLightDirectional) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return table[a].intensity.w > table[b].intensity.w; });
  if (order.size() > maxLights) order.resize(maxLights);

  // The guard band: the view's own directions end kLightShadowGuardTexels inside its tile.
  const double guard = 1.0 / (1.0 - 2.0 * double(shared::kLightShadowGuardTexels) / tileTexels);
  const auto viewCount = [&](const shared::GpuLight& l) {
    if (l.type != shared::kLightSpot) return 6u;
    const double tanOuter = std::sqrt(std::max(1.0 - double(l.cosOuter) * l.cosOuter, 0.0)) / std::max(double(l.cosOuter), 1e-6);
    return l.cosOuter > 0.0f && tanOuter <= shared::kLightShadowMaxSpotTan ? 1u : 6u;
  };
  // Keep the most powerful lights whose views fit an atlas of at most kLightShadowAtlasMax squared.
  const uint32_t maxColumns = std::max(1u, kLightShadowAtlasMax / tileTexels);
  const uint32_t maxTiles = maxColumns * maxColumns;
  uint32_t tiles = 0;
  std::vector<size_t> kept;
  for (size_t i : order) {
    const uint32_t n = viewCount(table[i]);
    if (tiles + n > maxTiles) break;
    tiles += n;
    kept.push_back(i);
  }
  if (tiles == 0) return plan;
  plan.columns = std::min(tiles, maxColumns);
  plan.rows = (tiles + plan.columns - 1) / plan.columns;

  static const glm::dvec3 kFaces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (size_t i : kept) {
    shared::GpuLight& l = table[i];
    const glm::dvec3 eye(l.position);
    // The far plane reaches the farthest corner of the scene (or the light's range).
    double farPlane = 0.0;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? sceneMax.x : sceneMin.x, (c & 2) ? sceneMax.y : sceneMin.y,
                              (c & 4) ? sceneMax.z : sceneMin.z);
      farPlane = std::max(farPlane, glm::length(corner - eye));
    }
    if (l.position.w > 0.0f) farPlane = std::min(farPlane, double(l.position.w));
    farPlane = std::max(farPlane * 1.01, 1e-30);
    l.shadowView = uint32_t(plan.views.size());
    if (viewCount(l) == 1) {
      const double tanOuter = std::sqrt(std::max(1.0 - double(l.cosOuter) * l.cosOuter, 0.0)) / double(l.cosOuter);
      plan.views.push_back(makeView(eye, glm::normalize(glm::dvec3(l.direction)), tanOuter * guard, farPlane, tileTexels, 1));
    } else {
      for (const auto& f : kFaces) plan.views.push_back(makeView(eye, f, guard, farPlane, tileTexels, 6));
    }
  }
  for (uint32_t t = 0; t < plan.views.size(); ++t) {
    const float cols = float(plan.columns), rows = float(plan.rows);
    plan.views[t].tile = glm::vec4(float(t % plan.columns) / cols, float(t / plan.columns) / rows, 1.0f / cols, 1.0f / rows);
  }
  return plan;
}

}  // namespace tl::lighting
