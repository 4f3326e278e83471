// What every pass of the RT path shares: the frame, the blue noise, the G-buffer's depth
// and normal, and the one ray generation (shared/rt.h) they all repeat.
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/rt.h"

layout(set = 0, binding = kRtBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kRtBindingBlueNoise) uniform sampler2D blueNoise;
layout(set = 0, binding = kRtBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kRtBindingNormal) uniform sampler2D gNormal;
layout(push_constant) uniform Push { RtPush push; };

#include "common/camera.glsl"

bool finite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

vec3 pixelNormal(ivec2 p) { return tlOctDecode(texelFetch(gNormal, p, 0).xy); }

// The index of this pass's rays in the sequence of all rays a pixel takes: the frame, or with
// two rays per pixel twice the frame plus which of the two (so the pair is two successive
// steps of the same sequence).
uint rayIndex() { return push.raysPerPixel == 2u ? 2u * frame.frameIndex + push.sampleIndex : frame.frameIndex; }

// Metro's noise addressing: the 64x64 tile shifts by half a tile on odd steps, and the R2
// rotation (tlRtRandom) moves every value each step.
vec3 pixelRayDirection(ivec2 p, vec3 normal) {
  uint index = rayIndex();
  ivec2 t = (p + ivec2(32 * (index & 1u))) & ivec2(kRtBlueNoiseSize - 1u);
  vec2 u = tlRtRandom(texelFetch(blueNoise, t, 0).xy, index);
  return tlRtRayDirection(normal, u);
}

// The ray starts off the surface by a few ULPs of its position (shared/ray_origin.h).
vec3 pixelRayOrigin(vec3 position, vec3 normal) { return tlOffsetRayOrigin(position, normal, frame.sceneScale); }

// With fewer rays than pixels the passes that trace launch fewer invocations, each mapped to
// a pixel that traces this frame (no idle SIMD lanes on skipped pixels): half as many for the
// checkerboard, a quarter (one per 2x2 block) at half resolution.
ivec2 tracedPixel(ivec2 q) {
  if (push.rayPattern == kRtRaysCheckerboard) return ivec2(2 * q.x + int((uint(q.y) + frame.frameIndex) & 1u), q.y);
  if (push.rayPattern == kRtRaysHalfResolution) return 2 * q + tlRtBlockOffset(frame.frameIndex);
  return q;
}
