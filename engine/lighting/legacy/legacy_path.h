// Names of the legacy path's graph resources, and the clipmap fit (pure, unit-tested).
#pragma once

#include "graph/resource_name.h"
#include "scene/scene.h"
#include "shared/legacy.h"

namespace tl::lighting {

inline constexpr graph::ImageName kLegacyAoRaw{"legacy.ao.raw"};
inline constexpr graph::ImageName kVoxelRadiance{"legacy.voxel.clipmap"};
inline constexpr graph::ImageName kVoxelRadianceMips{"legacy.voxel.clipmapMips"};
inline constexpr graph::ImageName kVoxelSeeds{"legacy.voxel.seeds"};  // rooms: where direct light enters the air (level 0)
inline constexpr graph::ImageName kVoxelReach{"legacy.voxel.reach"};  // rooms: the air light reaches (level 0)
inline constexpr graph::BufferName kVoxelReachUnsettled{"legacy.voxel.reachUnsettled"};  // rooms: the flood's last round's count
inline constexpr graph::ImageName kConeShY{"legacy.cones.shY"};
inline constexpr graph::ImageName kConeCoCgAo{"legacy.cones.coCgAo"};
inline constexpr graph::ImageName kLegacyAo{"legacy.ao"};
inline constexpr graph::ImageName kLegacyShY{"legacy.gi.shY"};
inline constexpr graph::ImageName kLegacyCoCg{"legacy.gi.coCg"};
inline constexpr graph::ImageName kLegacyHistRadiance{"legacy.history.radiance"};
inline constexpr graph::ImageName kLegacyHistDepth{"legacy.history.depth"};
inline constexpr graph::ImageName kLegacySsao{"legacy.ssao"};  // SSAO accumulated over frames, reduced resolution
inline constexpr graph::ImageName kLegacyHistSsao{"legacy.history.ssao"};
inline constexpr graph::ImageName kLegacyHiz{"legacy.reflections.hiz"};  // hierarchical depth: nearest depth per 2^m cell, mip m
inline constexpr graph::ImageName kLegacyReflections{"legacy.reflections"};
// legacyReflectionDivisor 2: the reflections of one pixel of each 2x2 block, before the upsample.
inline constexpr graph::ImageName kLegacyReflectionsReduced{"legacy.reflections.reduced"};

struct LegacyClipmapFit {
  shared::LegacyClipmap clipmap{};
};

// Levels of `resolution`^3 voxels (rounded up to a power of two in 16..256) around the
// camera, the finest `level0Extent` wide (<= 0: the scene's largest side, +2%), as many levels
// as it takes to span the scene (at most maxLevels). Each level is
// clamped into the scene's bounds, so a scene that fits the finest level needs one.
LegacyClipmapFit fitLegacyClipmap(const scene::Bounds& bounds, const glm::dvec3& camera, uint32_t resolution,
                                  float level0Extent, uint32_t maxLevels);

}  // namespace tl::lighting
