// Names of the legacy path's graph resources, and the clipmap fit (pure, unit-tested).
#pragma once

#include "scene/scene.h"
#include "shared/legacy.h"

namespace tl::lighting {

inline constexpr const char* kLegacyAoRaw = "legacy.ao.raw";
inline constexpr const char* kVoxelRadiance = "legacy.voxel.clipmap";
inline constexpr const char* kVoxelRadianceMips = "legacy.voxel.clipmapMips";
inline constexpr const char* kVoxelSeeds = "legacy.voxel.seeds";  // rooms: where direct light enters the air (level 0)
inline constexpr const char* kVoxelReach = "legacy.voxel.reach";  // rooms: the air light reaches (level 0)
inline constexpr const char* kVoxelReachUnsettled = "legacy.voxel.reachUnsettled";  // rooms: the flood's last round's count
inline constexpr const char* kConeShY = "legacy.cones.shY";
inline constexpr const char* kConeCoCgAo = "legacy.cones.coCgAo";
inline constexpr const char* kLegacyAo = "legacy.ao";
inline constexpr const char* kLegacyShY = "legacy.gi.shY";
inline constexpr const char* kLegacyCoCg = "legacy.gi.coCg";
inline constexpr const char* kLegacyHistRadiance = "legacy.history.radiance";
inline constexpr const char* kLegacyHistDepth = "legacy.history.depth";
inline constexpr const char* kLegacySsao = "legacy.ssao";  // SSAO accumulated over frames, reduced resolution
inline constexpr const char* kLegacyHistSsao = "legacy.history.ssao";
inline constexpr const char* kLegacyHiz = "legacy.reflections.hiz";  // hierarchical depth: nearest depth per 2^m cell, mip m
inline constexpr const char* kLegacyReflections = "legacy.reflections";

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
