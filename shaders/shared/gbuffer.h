// The G-buffer's bindings and encodings, shared by the G-buffer pass (writer), the
// composite, and later lighting paths. The channel table itself (name, format, meaning)
// lives once in engine/lighting/common/gbuffer_pass.h (kGbufferChannels).
#ifndef TL_SHARED_GBUFFER_H
#define TL_SHARED_GBUFFER_H
#include "common.h"

TL_BEGIN
// The dielectric's F0 (KHR_materials_ior, KHR_materials_specular; shared/shading.h) as the
// G-buffer keeps it: one grey value (the luminance of a tinted F0), stored as sqrt(F0) in 8 bits
// so that glTF's 0.04 is exact (51 / 255 squared) and any F0 is within 2% of itself (half a step).
TL_FN float tlGbufferEncodeF0(vec3 f0) { return sqrt(clamp(tlLuminance(f0), 0.0f, 1.0f)); }
TL_FN float tlGbufferDecodeF0(float stored) { return stored * stored; }

// Colour attachment locations of the G-buffer pass.
TL_CONST uint kGbufferBaseColor = 0;   // RGBA8_SRGB: base colour (linear once sampled), a the dielectric's F90
TL_CONST uint kGbufferNormal = 1;      // RG16_SNORM: octahedral world shading normal
TL_CONST uint kGbufferMaterial = 2;    // RGBA8: r roughness, g metalness, b the dielectric's F0, a occlusion
TL_CONST uint kGbufferEmissive = 3;    // RGBA16F: emitted radiance
TL_CONST uint kGbufferMotion = 4;      // RG16F: screen motion in UV, current - previous
TL_CONST uint kGbufferInstanceId = 5;  // R32UI: instance index + 1 (0: nothing)
TL_CONST uint kGbufferColorCount = 6;
// The G-buffer pass's set-0 buffer of deforming meshes' previous positions (vec4 each,
// GpuInstance::previousPositionOffset; bound only in scenes that deform).
TL_CONST uint kGbufferPreviousPositions = 1;

// Push constants of the G-buffer and shadow passes: no per-draw data is needed (the
// instance index arrives as gl_InstanceIndex through firstInstance).
struct RasterPush {
  mat4 viewProj;  // shadow pass: the sun's; G-buffer pass: unused (frame constants)
};

// Bindings of the composite pass (set 0).
TL_CONST uint kCompositeBaseColor = 1;
TL_CONST uint kCompositeNormal = 2;
TL_CONST uint kCompositeMaterial = 3;
TL_CONST uint kCompositeEmissive = 4;
TL_CONST uint kCompositeDepth = 5;
TL_CONST uint kCompositeShadow = 6;
TL_CONST uint kCompositeOutput = 7;
TL_CONST uint kCompositeAo = 8;        // the path's AO (r), 1 = unoccluded
TL_CONST uint kCompositeShY = 9;       // the path's diffuse irradiance, L1 SH of luma (shared/sh.h)
TL_CONST uint kCompositeCoCg = 10;     // its chroma (xy)
TL_CONST uint kCompositeShadowDepth = 11;  // the sun shadow map again, plain sampler (PCSS blocker search)
// The composite.stages pass: the same inputs (subset), these outputs.
TL_CONST uint kCompositeStageAo = 12;          // r16f: the AO the composite applied (0 on the sky)
TL_CONST uint kCompositeStageIrradiance = 13;  // rgba16f: the diffuse irradiance it used (0 on the sky)

// The far field the GI fades to beyond the blend distance (another path's: legacy's).
TL_CONST uint kCompositeFarShY = 14;
TL_CONST uint kCompositeFarCoCg = 15;
TL_CONST uint kCompositeFarAo = 16;
TL_CONST uint kCompositeLights = 17;  // rgba16f: the light table's reflected radiance (lights.direct; a: its specular lobes' luminance)
TL_CONST uint kCompositeSunVisibility = 18;  // r16f: the sun's visibility from shadow.sun.hybrid (HRTS)
TL_CONST uint kCompositeSpecular = 19;  // rgba16f: the path's traced specular, demodulated (rgb), its weight (a) (shared/rt_specular.h)
// composite.stages: the radiance the surface reflects through its diffuse layer and through its
// specular lobes (rgba16f each; 0 on the sky), the same split as the reference's lobes.
TL_CONST uint kCompositeStageDiffuse = 20;
TL_CONST uint kCompositeStageSpecular = 21;

TL_CONST uint kCompositeHasAo = 1u;
TL_CONST uint kCompositeHasGi = 2u;
TL_CONST uint kCompositeAoOnGi = 4u;
TL_CONST uint kCompositeHasFarGi = 8u;
TL_CONST uint kCompositeSpecularGi = 16u;  // specular from the path's SH (else the sky's, times AO)
TL_CONST uint kCompositeHasLights = 32u;   // lights.direct is bound: add it
TL_CONST uint kCompositeHasSunVisibility = 64u;  // shadow.sun.visibility is bound: the sun's shadow from it, not the map
TL_CONST uint kCompositeHasTracedSpecular = 128u;  // the path traced reflections (kCompositeSpecular is bound)
struct CompositePush {
  uint flags;               // kCompositeHas*: which path outputs are bound
  float giBlendDistance;    // beyond this view distance GI fades to the far field, else the sky (0: never)
  float giBlendWidth;       // over this many metres
  float openSkyDirectionality;     // a uniform sky's directionality in the path's SH (shared/sh.h)
  float farOpenSkyDirectionality;  // and in the far field's
  uint ibufferStage;    // ibuffer.light: kIbufferStage* (shared/redeferred.h)
  uint ibufferPattern;  // ibuffer.light: kIbufferPattern*
  uint pad2;
};

// Bindings of the tonemap pass (set 0).
TL_CONST uint kTonemapInput = 1;
TL_CONST uint kTonemapOutput = 2;
TL_END
#endif
