// The legacy path's settings: GTAO, the voxel clipmap, cones, rooms and reflections.
// One line per setting, the columns of TL_RENDER_SETTINGS (render_settings.h), which gathers
// this group and names its owner: `owner` below is that name, so no line restates it.
// A new setting of this group is one line here.
#pragma once

// clang-format off
#define TL_LEGACY_SETTINGS(X, owner) \
  X(float, legacyAoRadius, 0.0f, 0.0f, 1e9f, "m", owner, "legacy", kSettingAuto, "reach of SSAO and voxel AO") \
  X(float, legacyAoThickness, 0.1f, 0.0f, 1.0f, "", owner, "legacy", kSettingPlain, "GTAO thickness heuristic: how fast a horizon falls back behind thin occluders (0 infinitely thick, 1 paper thin)") \
  X(uint32_t, legacyAoSlices, 1, 1, 16, "slices", owner, "legacy", kSettingTune, "GTAO slice directions per pixel and frame (the 2x2 interleave and the accumulation supply more)") \
  X(uint32_t, legacyAoSteps, 4, 1, 64, "samples", owner, "legacy", kSettingTune, "GTAO depth samples per direction and side") \
  X(uint32_t, legacyAoDivisor, 2, 1, 2, "", owner, "legacy", kSettingPow2 | kSettingTune, "SSAO resolution divisor: 1 full, 2 half") \
  X(uint32_t, legacyAoFrames, 8, 1, 64, "frames", owner, "", kSettingPlain, "SSAO temporal accumulation window (1: off)") \
  X(uint32_t, legacyConeDivisor, 4, 1, 4, "", owner, "", kSettingPow2 | kSettingTune, "cone tracing resolution divisor: 1 full, 2 half, 4 quarter") \
  X(uint32_t, legacyVoxelResolution, 64, 8, 256, "voxels", owner, "legacy", kSettingPow2 | kSettingTune, "clipmap resolution R: each level holds R^3 voxels") \
  X(float, legacyLevel0Extent, 0.0f, 0.0f, 1e9f, "m", owner, "legacy", kSettingAuto, "side of the finest clipmap level; coarser levels double it until the scene is covered") \
  X(uint32_t, legacyMaxLevels, 4, 1, 4, "levels", owner, "legacy", kSettingTune, "clipmap levels at most") \
  X(float, legacyConeRange, 0.0f, 0.0f, 1e9f, "m", owner, "", kSettingAuto, "cones stop after this distance") \
  X(float, legacyConeStep, 1.0f, 0.2f, 2.0f, "x diameter", owner, "", kSettingTune, "cone step as a fraction of its diameter: smaller is slower and more exact") \
  X(uint32_t, legacyRoomSweeps, 4, 0, 64, "rounds", owner, "legacy", kSettingTune | kSettingFeature, "rooms: rounds of x, y and z sweeps that flood the finest level's air from its lit surfaces and open edges; cones in air no light reaches (a sealed room) gather nothing (0: off)") \
  X(bool, legacyScreenRadiance, true, 0, 1, "", owner, "legacy", kSettingTune | kSettingFeature, "voxels seen last frame take its shaded radiance, so light bounces more than once") \
  X(float, legacyReflectionRoughness, 0.5f, 0.0f, 1.0f, "roughness", owner, "", kSettingTune | kSettingFeature | kSettingReflections, "reflections: pixels below this roughness follow their mirror direction across the screen (last frame's image, through a hierarchical depth march) and through the voxels (a specular cone the lobe's width), blended into the SH specular over the top fifth of the range; 0: the SH specular everywhere") \
  X(uint32_t, legacyReflectionSteps, 64, 0, 1024, "steps", owner, "", kSettingTune | kSettingReflections, "reflections: the screen-space march's steps at most (0: the voxel cone alone)") \
  X(uint32_t, legacyReflectionDivisor, 1, 1, 2, "", owner, "", kSettingPow2 | kSettingTune | kSettingReflections, "reflections: 1 every pixel marched; 2 one pixel of each 2x2 block, the others filled from the blocks of their own material (roughness, metalness and F0 alike; weighted by depth and normal; a pixel they hardly stand for is marched itself)") \
  X(float, legacyMirrorRoughness, 0.02f, 0.0f, 1.0f, "roughness", owner, "", kSettingReflections, "reflections: at legacyReflectionDivisor 2, pixels at or below this roughness are marched at full resolution (a reduced reflection of a mirror is visibly blurred)") \
  X(bool, legacyPartialVoxels, true, 0, 1, "", owner, "", kSettingPlain, "deforming or moved instances re-voxelize only the voxels they and their shadows reach") \
  X(bool, legacyVoxelizeEveryFrame, false, 0, 1, "", owner, "", kSettingPlain, "rebuild the voxels every frame, even when nothing they hold changed") \
  X(uint32_t, legacySettleFrames, 4, 0, 64, "frames", owner, "", kSettingPlain, "after a change, rebuild the voxels this many more frames so bounces settle")
// clang-format on
