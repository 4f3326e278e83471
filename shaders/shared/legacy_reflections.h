// The legacy path's reflections (legacy/hiz_first.comp, legacy/hiz_reduce.comp,
// legacy/reflections.comp): the counterpart of
// the RT path's traced specular, with no ray tracing. For pixels below a roughness threshold,
// the mirror direction is marched through a hierarchical depth buffer (screen-space
// reflections); where the march finds a surface that was on screen last frame, that frame's
// image gives the light. Behind it, or where the march finds nothing, a specular cone through
// the voxel clipmap (VXGI's specular cones) gathers the light, its aperture from the lobe's
// width; what leaves the clipmap sees the sky. The two are blended by the march's confidence.
//
// Output (legacy.reflections, rgba16f, the same contract as the RT path's rt.specular): the
// lobe's mean incident radiance (rgb, demodulated: the composite multiplies it by the whole
// specular albedo) and the weight against the SH specular (a, shared/rt_specular.h's seam;
// 0: not traced).
//
// Hierarchical depth (legacy.reflections.hiz): mip 0 is the G-buffer's reversed-Z depth, mip
// m + 1 the largest (nearest) of mip m's 2x2 texels, so a texel of mip m bounds from the front
// everything in the 2^m x 2^m pixels it covers (sizes round up; a missing texel is skipped).
#ifndef TL_SHARED_LEGACY_REFLECTIONS_H
#define TL_SHARED_LEGACY_REFLECTIONS_H
#include "common.h"
#include "legacy.h"

TL_BEGIN
// Mips of the hierarchical depth at most: a 2^7 = 128-pixel cell is where a march gains nothing more.
TL_CONST uint kLegacyHizMaxMips = 8u;

struct LegacyReflectionPush {
  LegacyClipmap clipmap;
  float roughness;       // pixels below this roughness reflect (0: none)
  float coneRange;       // the specular cone stops after this distance (m; the diffuse cones' range)
  float coneStep;        // cone step as a fraction of its diameter
  uint screenHistory;    // 1: last frame's image and depth are valid (the march can use them)
  uint hizMips;          // mips of the hierarchical depth
  uint maxSteps;         // the march's iterations at most (0: no screen-space march)
  uint mode;             // kLegacyReflections*: every pixel, or the reduced march and its upsample
  float fullRoughness;   // kLegacyReflectionsUpsample: pixels at or below this roughness are computed, not upsampled
};

// Resolution (LegacyReflectionPush::mode, legacyReflectionDivisor). Full: every pixel is
// marched. Reduced: one pixel of each 2x2 block (its top-left) is marched into
// legacy.reflections.reduced (a 1: computed; 0: nothing to reflect there). Upsample: each pixel
// takes the reduced texels around it of its own material (the G-buffer's roughness, metalness
// and F0), bilinear and weighted by depth and normal, and is marched itself where they hardly
// stand for it or where it is mirror-like (at or below fullRoughness: a half-resolution
// reflection of a mirror is visibly blurred).
TL_CONST uint kLegacyReflectionsFull = 0u;
TL_CONST uint kLegacyReflectionsReduced = 1u;
TL_CONST uint kLegacyReflectionsUpsample = 2u;

// Bindings (set 0) beyond the legacy path's (shared/legacy.h): frame, depth, normal, voxels,
// mips, reach and last frame's image and depth keep theirs.
TL_CONST uint kLegacyBindingMaterial = 26;        // gbuffer.material: roughness (r), metalness (g), sqrt F0 (b)
TL_CONST uint kLegacyBindingBaseColor = 27;       // gbuffer.baseColor: base colour, F90 (a)
TL_CONST uint kLegacyBindingHiz = 28;             // hierarchical depth, all mips (sampled)
TL_CONST uint kLegacyBindingHizSource = 29;       // hiz_reduce.comp: the mip below (storage, r32f)
TL_CONST uint kLegacyBindingHizOut = 30;          // hiz_first.comp, hiz_reduce.comp: the mip written (storage, r32f)
TL_CONST uint kLegacyBindingReflections = 31;     // legacy.reflections (storage, rgba16f); the reduced pass's legacy.reflections.reduced
TL_CONST uint kLegacyBindingReflectionsReduced = 32;  // the upsample's input: legacy.reflections.reduced (sampled)
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::LegacyReflectionPush) == 112);
#endif
#endif
