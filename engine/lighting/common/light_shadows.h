// Shadow maps of point, spot and area lights for the direct and legacy paths (shared/lights.h
// GpuShadowView): which lights get them, each view's projection and its tile in the depth atlas.
// Pure, tested without a GPU; the session uploads the views and LightShadowPass draws them.
#pragma once

#include "graph/resource_name.h"
#include "scene/scene.h"
#include "shared/lights.h"

#include <cstdint>
#include <vector>

namespace tl::lighting {

// Graph names: the views (imported, only in frames that have them) and the atlas they draw.
inline constexpr graph::BufferName kLightShadowViews{"lights.shadowViews"};
inline constexpr graph::ImageName kLightShadowAtlas{"shadow.lightsDepth"};

// The atlas is at most this many texels on a side; lights that do not fit go unshadowed.
inline constexpr uint32_t kLightShadowAtlasMax = 16384;

struct LightShadowPlan {
  std::vector<shared::GpuShadowView> views;
  uint32_t tileTexels = 0;
  uint32_t columns = 0, rows = 0;  // tiles; 0 x 0: no shadowed light (no atlas, no pass)
  uint32_t atlasWidth() const { return columns * tileTexels; }
  uint32_t atlasHeight() const { return rows * tileTexels; }
};

// Gives the `maxLights` most powerful point, spot and area lights of `table` (buildLightTable's,
// camera-relative) shadow views of `tileTexels` squared and writes their first view into
// GpuLight::shadowView (kNoLightShadow for the others). `sceneMin`/`sceneMax` bound every caster
// and receiver, camera-relative: they place each view's far plane.
LightShadowPlan planLightShadows(std::vector<shared::GpuLight>& table, uint32_t tileTexels, uint32_t maxLights,
                                 const glm::dvec3& sceneMin, const glm::dvec3& sceneMax);

}  // namespace tl::lighting
