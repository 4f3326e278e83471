#include "lighting/legacy/voxel_regions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tl::lighting {

scene::Bounds shadowSweptBounds(const scene::Bounds& box, const glm::dvec3& sunTravel, const scene::Bounds& scene,
                                double margin) {
  if (!box.valid()) return box;
  // The sweep ends where the whole box has left the scene along some axis: past that,
  // nothing is left to shadow.
  double reach = std::numeric_limits<double>::max();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(sunTravel[a]) < 1e-9) continue;
    const double t = sunTravel[a] > 0.0 ? (scene.max[a] - box.min[a]) / sunTravel[a] : (scene.min[a] - box.max[a]) / sunTravel[a];
    reach = std::min(reach, std::max(t, 0.0));
  }
  if (!scene.valid() || reach == std::numeric_limits<double>::max()) reach = 0.0;
  scene::Bounds swept = box;
  swept.extend(scene::Bounds{box.min + reach * sunTravel, box.max + reach * sunTravel});
  swept.min -= glm::dvec3(margin);
  swept.max += glm::dvec3(margin);
  if (scene.valid()) {
    // The box itself stays whole (it may stick out of stale scene bounds); its shadow is clipped.
    swept.min = glm::max(swept.min, glm::min(scene.min, box.min));
    swept.max = glm::min(swept.max, glm::max(scene.max, box.max));
  }
  return swept;
}

VoxelRegion voxelRegionOf(const shared::LegacyClipmap& clipmap, uint32_t level, const glm::dvec3& camera,
                          const scene::Bounds& box) {
  if (!box.valid() || level >= clipmap.levels) return {};
  const glm::vec4 l = clipmap.levelMin[level];
  const glm::dvec3 origin = glm::dvec3(glm::vec3(l)) + camera;
  const double voxel = l.w;
  const int R = int(clipmap.resolution);
  VoxelRegion r;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::floor((box.min[a] - origin[a]) / voxel) - 1.0;
    const double hi = std::floor((box.max[a] - origin[a]) / voxel) + 2.0;  // exclusive
    r.min[a] = int(std::clamp(lo, 0.0, double(R)));
    r.max[a] = int(std::clamp(hi, 0.0, double(R)));
  }
  return r.empty() ? VoxelRegion{} : r;
}

scene::Bounds worldBoundsOf(const shared::LegacyClipmap& clipmap, uint32_t level, const glm::dvec3& camera,
                            const VoxelRegion& region) {
  const glm::vec4 l = clipmap.levelMin[level];
  const glm::dvec3 origin = glm::dvec3(glm::vec3(l)) + camera;
  return {origin + glm::dvec3(region.min) * double(l.w), origin + glm::dvec3(region.max) * double(l.w)};
}

namespace {

VoxelRegion unite(const VoxelRegion& a, const VoxelRegion& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

bool overlap(const VoxelRegion& a, const VoxelRegion& b) {
  return glm::all(glm::lessThan(a.min, b.max)) && glm::all(glm::lessThan(b.min, a.max));
}

// Worth one region: they overlap, or their union adds at most a quarter to what both hold
// (each region costs a clear, draws per axis and round, and a dispatch per mip).
bool shouldMerge(const VoxelRegion& a, const VoxelRegion& b) {
  return overlap(a, b) || 4 * unite(a, b).voxels() <= 5 * (a.voxels() + b.voxels());
}

}  // namespace

std::vector<VoxelRegion> mergeVoxelRegions(std::vector<VoxelRegion> regions) {
  std::erase_if(regions, [](const VoxelRegion& r) { return r.empty(); });
  // Greedy: merge any pair that should be one until no pair should; a union can reach a
  // third region, so start over after each merge (a few dozen regions at most).
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < regions.size() && !merged; ++i)
      for (size_t j = i + 1; j < regions.size() && !merged; ++j)
        if (shouldMerge(regions[i], regions[j])) {
          regions[i] = unite(regions[i], regions[j]);
          regions.erase(regions.begin() + std::ptrdiff_t(j));
          merged = true;
        }
  }
  return regions;
}

VoxelRegion mipFootprint(const VoxelRegion& region, uint32_t mip) {
  if (region.empty()) return {};
  // Texel c of mip m covers voxels [c 2^m, (c + 1) 2^m): from the one holding min to the one holding max - 1.
  return {region.min >> int(mip), ((region.max - 1) >> int(mip)) + 1};
}

}  // namespace tl::lighting
