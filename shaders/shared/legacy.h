// The legacy lighting path ("RTX OFF", engine/lighting/legacy/, shaders/legacy/): horizon-based
// SSAO (GTAO), a voxel clipmap lit by the sun through the shadow map, cone-traced diffuse
// irradiance and voxel AO. Bindings, push constants and the clipmap layout, shared by C++
// and GLSL.
//
// Clipmap layout. Level l is a cube of R^3 voxels of size voxelSize * 2^l, placed around the
// camera (clamped to the scene's bounds so a small scene needs one level). All levels are
// stacked along z in one 3D image: level l occupies z in [l R, (l+1) R).
//   voxels: 6R x R x (N R), rgba16f, anisotropic: face block f (x in [f R, (f+1) R)) holds,
//           for direction +x, -x, +y, -y, +z, -z, the diffuse radiance the voxel sends that
//           way (rgb, premultiplied by opacity) and its opacity seen from that side (a). A thin wall's lit and unlit sides land
//             in opposite faces of the same voxel, so a cone from inside sees the unlit one:
//             that is what keeps light from leaking through walls one voxel thick. Mips
//             composite the two children along each face's axis front to back (opacity and
//             premultiplied radiance), then average across it.
// Mips: a second image holds levels 1.. of the chain (R/2 and smaller), so every graph
// resource has one writer; cone tracing reads mip 0 from the first.
// Rooms (finest level only, R^3 r8ui each):
//   seeds: 1 where an empty voxel lies in front of a surface that direct light reaches (the
//          sun, the light table, emission: what voxelize.frag injects before any feedback).
//   reach: the level's empty voxels that light can reach, flooded through empty voxels
//          (6-connected) from the seeds and from the level's outer faces (the sky, or what
//          lies beyond the level): kLegacyReach* below. A surface voxelized along all three
//          axes separates the air on its two sides, so air no light reaches is a sealed room
//          that holds no light, and cones starting there gather none (cones.comp). The flood
//          runs a fixed number of rounds; where its last round still reached voxels it may not
//          have settled (air light reaches could still read sealed), and the cones ignore it.
#ifndef TL_SHARED_LEGACY_H
#define TL_SHARED_LEGACY_H
#include "common.h"

TL_BEGIN
TL_CONST uint kLegacyMaxLevels = 4u;

// The diffuse cones (legacy/cones.comp): one along the normal and five tilted by 55 degrees,
// 60 degree apertures, weighted by their cosine so the weights sum to pi (Lambert's integral).
// Each cone's radiance is projected into the RT path's SH layout with the RT sample weight
// w / (1/4 + cos/2), so the SH resolves to exactly sum(w L) at the pixel's normal.
TL_CONST float kLegacyConeTanHalfAperture = 0.57735f;  // 60 degree cones
TL_CONST float kLegacyConeRingTilt = 0.95993f;         // 55 degrees: six cones cover the hemisphere
TL_CONST float kLegacyConeRingCos = 0.57358f;          // cos(55 degrees)
TL_CONST float kLegacyConeAxisWeight = 0.81222f;       // pi / (1 + 5 cos(55 deg))
// The cones' SH of a uniform sky has directionality |L1| / (sqrt(3) L0) = (fa + 5 fr c) /
// (fa + 5 fr) with fa = 1 / (1/4 + 1/2), fr = c / (1/4 + c/2), c = cos(55 deg): 0.6587 (the
// RT path's cosine samples: kShOpenSkyDirectionality, 0.6094).
TL_FN float tlLegacyOpenSkyDirectionality() {
  float c = kLegacyConeRingCos;
  float fa = 1.0f / 0.75f, fr = c / (0.25f + 0.5f * c);
  return (fa + 5.0f * fr * c) / (fa + 5.0f * fr);
}

struct LegacyClipmap {
  vec4 levelMin[4];    // xyz: camera-relative minimum corner of level l, w: its voxel size (m)
  uint resolution;     // R
  uint levels;         // N
  uint mipCount;       // mips of the mip images (levels 1.. of the chain)
  uint roomGate;       // 1: the reach image is bound and cones from sealed, unlit air gather nothing
};

struct LegacyPush {
  LegacyClipmap clipmap;
  float aoRadius;          // SSAO and voxel AO radius (m)
  float aoThickness;       // GTAO thickness heuristic: how fast a horizon falls back behind thin occluders, 0..1
  uint aoSlices;           // directions per pixel
  uint aoSteps;            // samples per direction and side
  float coneRange;         // GI cones stop after this distance (m)
  float coneStep;          // step as a fraction of the cone diameter
  uint aoDivisor;          // SSAO resolution: 1 full, 2 half
  uint axis;               // voxelization: projection axis (0 x, 1 y, 2 z) + 3 x level
  uint coneDivisor;        // cone tracing resolution: 1 full, 2 half, 4 quarter
  uint voxelRound;         // voxelization: 0 opacity of every face, 1 radiance of the faces a surface looks out of
  uint screenRadiance;     // voxelization: surfaces seen last frame take their shaded radiance from it
  uint aoHistory;          // SSAO temporal pass: frames the AO may accumulate (0: no valid history)
};

// Push constants of the voxel passes (voxelize, clear, mips), which need none of the
// screen-space settings above but a region: partial updates clear, re-voxelize and re-filter
// only the voxels a change can reach. The region is in the voxels of one level (of one mip,
// for the mips), the same box for each of the six face blocks; a full rebuild's region is
// the whole level.
struct LegacyVoxelPush {
  LegacyClipmap clipmap;
  uint axis;            // voxelize: projection axis (0 x, 1 y, 2 z) + 3 x level; reach sweeps: the axis swept
  uint voxelRound;      // voxelize: 0 opacity of every face, 1 radiance of the faces a surface looks out of
  uint screenRadiance;  // voxelize: surfaces seen last frame take their shaded radiance from it
  uint level;           // clear and mips: the clipmap level the region lies in; reach sweeps: 1 in the last round
  ivec4 regionMin;      // xyz: first voxel of the region (inclusive)
  ivec4 regionMax;      // xyz: end of the region (exclusive)
};

// Bindings (set 0).
TL_CONST uint kLegacyBindingFrame = 0;
TL_CONST uint kLegacyBindingDepth = 1;
TL_CONST uint kLegacyBindingNormal = 2;
TL_CONST uint kLegacyBindingShadow = 3;       // sun shadow map (compare sampler)
TL_CONST uint kLegacyBindingRadiance = 5;     // voxels, mip 0 (storage or sampled)
TL_CONST uint kLegacyBindingRadianceMips = 7; // voxels, mips 1..
TL_CONST uint kLegacyBindingAoRaw = 8;        // half-res SSAO
TL_CONST uint kLegacyBindingConeShY = 9;      // half-res cone-traced SH luma
TL_CONST uint kLegacyBindingConeCoCgAo = 10;  // half-res chroma (xy), voxel AO (z)
TL_CONST uint kLegacyBindingOutAo = 11;
TL_CONST uint kLegacyBindingOutShY = 12;
TL_CONST uint kLegacyBindingOutCoCg = 13;
TL_CONST uint kLegacyBindingMipSrcRadiance = 15;
TL_CONST uint kLegacyBindingPrevRadiance = 16;  // last frame's composite radiance
TL_CONST uint kLegacyBindingPrevDepth = 17;     // last frame's G-buffer depth
TL_CONST uint kLegacyBindingAoHistory = 18;     // last frame's accumulated SSAO: AO (r), view depth (g), frames (b)
TL_CONST uint kLegacyBindingMotion = 19;        // gbuffer.motion
TL_CONST uint kLegacyBindingSsaoOut = 20;       // reduced-res accumulated SSAO: AO (r), view depth (g), frames (b)
TL_CONST uint kLegacyBindingVertices = 21;      // voxelize: the scene's vertex buffer (tl::scene::Vertex, 12 floats)
TL_CONST uint kLegacyBindingIndices = 22;       // voxelize: the scene's index buffer
TL_CONST uint kLegacyBindingSeeds = 23;         // rooms: empty voxels in front of directly lit surfaces (r8ui, level 0)
TL_CONST uint kLegacyBindingReach = 24;         // rooms: kLegacyReach* per voxel of level 0 (r8ui)
TL_CONST uint kLegacyBindingReachUnsettled = 25;  // rooms: one uint, the voxels the flood's last round still reached
// Slots a shader names by its own role for them (the number is the slot above it shares).
TL_CONST uint kLegacyUpsampleSsao = 20;       // legacy/upsample.comp: the accumulated SSAO it upsamples (what ssao_temporal wrote)
TL_CONST uint kLegacyReachInitVoxels = 15;    // legacy/voxel_reach_init.comp: the voxels' mip 0, read for what is solid

// Values of the reach image.
TL_CONST uint kLegacyReachSealed = 0u;  // empty, and no light reaches it
TL_CONST uint kLegacyReachLit = 1u;     // empty, and light reaches it
TL_CONST uint kLegacyReachSolid = 2u;   // a surface's voxel
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::LegacyClipmap) == 80);
static_assert(sizeof(tl::shared::LegacyPush) == 128);
static_assert(sizeof(tl::shared::LegacyVoxelPush) == 128);
#endif
#endif
