// The G-buffer's bindings and encodings, shared by the G-buffer pass (writer), the
// composite, and later lighting paths. The channel table itself (name, format, meaning)
// lives once in engine/lighting/common/gbuffer_layout.h.
#ifndef TL_SHARED_GBUFFER_H
#define TL_SHARED_GBUFFER_H
#include "common.h"

TL_BEGIN
// Colour attachment locations of the G-buffer pass.
TL_CONST uint kGbufferBaseColor = 0;   // RGBA8_SRGB: base colour (linear once sampled), a: 1
TL_CONST uint kGbufferNormal = 1;      // RG16_SNORM: octahedral world shading normal
TL_CONST uint kGbufferMaterial = 2;    // RGBA8: r roughness, g metalness, b geometric-normal sign, a 1
TL_CONST uint kGbufferEmissive = 3;    // RGBA16F: emitted radiance
TL_CONST uint kGbufferMotion = 4;      // RG16F: screen motion in UV, current - previous
TL_CONST uint kGbufferInstanceId = 5;  // R32UI: instance index + 1 (0: nothing)
TL_CONST uint kGbufferColorCount = 6;

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

// Bindings of the tonemap pass (set 0).
TL_CONST uint kTonemapInput = 1;
TL_CONST uint kTonemapOutput = 2;
TL_END
#endif
