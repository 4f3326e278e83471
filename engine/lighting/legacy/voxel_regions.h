// Which voxels of the legacy clipmap a scene change can reach (pure, unit-tested): a partial
// update clears, re-voxelizes and re-filters only those, the way VXAO re-voxelizes only the
// changed regions of its clipmap.
#pragma once

#include "scene/scene.h"
#include "shared/legacy.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace tl::lighting {

// A box of voxels [min, max) of one clipmap level (or of one of its mips).
struct VoxelRegion {
  glm::ivec3 min{0};
  glm::ivec3 max{0};
  bool empty() const { return max.x <= min.x || max.y <= min.y || max.z <= min.z; }
  int64_t voxels() const { return empty() ? 0 : int64_t(max.x - min.x) * (max.y - min.y) * (max.z - min.z); }
  bool operator==(const VoxelRegion&) const = default;
};

// What a change of `box` (world space: where the geometry was and is) can alter in the
// voxels, which hold sunlight injected through the shadow map: the box and the shadow it
// casts, i.e. the box swept along the sun's travel direction `sunTravel` until it leaves
// `scene`, grown by `margin` metres (the shadow filter's reach), clipped to `scene`.
scene::Bounds shadowSweptBounds(const scene::Bounds& box, const glm::dvec3& sunTravel, const scene::Bounds& scene,
                                double margin);

// The voxels of `level` that world-space `box` touches, with one voxel of margin against
// rounding, clamped to the level (empty when it misses). `camera` is the world position the
// clipmap's camera-relative corners are relative to.
VoxelRegion voxelRegionOf(const shared::LegacyClipmap& clipmap, uint32_t level, const glm::dvec3& camera,
                          const scene::Bounds& box);

// The world-space box a region of `level` covers.
scene::Bounds worldBoundsOf(const shared::LegacyClipmap& clipmap, uint32_t level, const glm::dvec3& camera,
                            const VoxelRegion& region);

// Unions regions that overlap, or whose union costs little more than both (nearby changes
// become one region), until no two overlap: then no voxel is cleared or drawn twice, and the
// surfaces sharing a voxel are drawn in the full rebuild's order.
std::vector<VoxelRegion> mergeVoxelRegions(std::vector<VoxelRegion> regions);

// The texels of mip `mip` (1: half resolution) whose children a change of `region` (mip 0)
// alters.
VoxelRegion mipFootprint(const VoxelRegion& region, uint32_t mip);

}  // namespace tl::lighting
