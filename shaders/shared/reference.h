// The reference path tracer (engine/lighting/reference/): bindings, push constants,
// per-instance geometry and the payload its shaders exchange.
#ifndef TL_SHARED_REFERENCE_H
#define TL_SHARED_REFERENCE_H
#include "common.h"

TL_BEGIN
TL_CONST uint kRefBindingFrame = 0;      // FrameConstants (shared/frame.h)
TL_CONST uint kRefBindingTlas = 1;
TL_CONST uint kRefBindingAccum = 2;      // rgba32f: sum of samples (persistent)
TL_CONST uint kRefBindingRadiance = 3;   // rgba32f: the estimate, sum / count
TL_CONST uint kRefBindingGeometry = 4;   // RefInstanceGeometry[]
TL_CONST uint kRefBindingVertices = 5;   // scene vertices as floats (kVertexFloats per vertex, shared/scene.h)
TL_CONST uint kRefBindingIndices = 6;    // scene indices
TL_CONST uint kRefBindingAoAccum = 7;    // r32f: sum of AO samples at the primary hit (persistent)
TL_CONST uint kRefBindingAo = 8;         // r32f: ambient occlusion at the AO radius, sum / count
TL_CONST uint kRefBindingIrradianceAccum = 9;  // rgba32f: sum of irradiance samples (rgb) and their count (a)
TL_CONST uint kRefBindingIrradiance = 10;      // rgba32f: diffuse irradiance at the primary hit, sum / count
TL_CONST uint kRefBindingDepthAccum = 11;  // rgba32f: sums of the radiance by depth group (rgb) and their count (a)
TL_CONST uint kRefBindingDepth0 = 12;      // rgba32f: the radiance of depth group 0, sum / count; groups 1..3 at 13..15

// The radiance by path depth (scattering events between light and camera), in four groups:
// 0-1 (emission and direct light), 2 (the first bounce), 3 (the second), 4 and more.
TL_CONST uint kRefDepthGroups = 4;


// Where an instance's triangles are in the scene's shared vertex/index buffers.
struct RefInstanceGeometry {
  uint firstIndex;
  int vertexOffset;
  uint material;
  uint pad;
};

struct RefPush {
  uint samplesSoFar;     // accumulated before this frame (0: start over)
  uint samplesPerFrame;
  uint maxBounces;       // scattering events per path (1 = direct light only, 2 = plus one bounce)
  uint seed;
  float aoRadius;        // reference AO: one cosine ray per sample from the primary hit, this long (m)
  uint sampleBase;       // the depth split's first sample index: the trace pass's samplesSoFar (same paths)
  uint pad1, pad2;
};

// What a closest-hit shader reports (hitT < 0: the ray missed).
struct RefHit {
  vec4 positionT;     // xyz camera-relative hit point, w hit distance
  vec4 normal;        // xyz shading normal facing the ray, w unused
  vec4 geometric;     // xyz geometric normal facing the ray
  vec4 baseColor;     // rgb, a roughness
  vec4 emission;      // rgb emitted radiance, a metallic
};
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::RefInstanceGeometry) == 16);
static_assert(sizeof(tl::shared::RefPush) == 32);
#endif
#endif
