#version 460
// Temporal accumulation of the RT path's raw SH irradiance and AO, before any spatial
// filtering (Metro Exodus): reproject with the motion vectors, reject history that falls
// off screen or belongs to another surface (view-depth test), and average with weight
// 1 / n, n growing to maxAccumFrames. Linear space throughout.
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"
#include "shared/sampling.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingMotion) uniform sampler2D gMotion;
layout(set = 0, binding = kRtBindingShY) uniform sampler2D rawShY;
layout(set = 0, binding = kRtBindingCoCg) uniform sampler2D rawCoCg;
layout(set = 0, binding = kRtBindingAo) uniform sampler2D rawAo;
layout(set = 0, binding = kRtBindingHistShY) uniform sampler2D historyShY;
layout(set = 0, binding = kRtBindingHistCoCgAo) uniform sampler2D historyCoCgAo;
layout(set = 0, binding = kRtBindingHistDepth) uniform sampler2D historyDepth;
layout(set = 0, binding = kRtBindingOutShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kRtBindingOutCoCgAo, rgba16f) uniform writeonly image2D outCoCgAo;
layout(set = 0, binding = kRtBindingOutDepth, r32f) uniform writeonly image2D outDepth;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  ivec2 src = p;
  bool noSample = false;  // half resolution: no traced sample nearby this frame (keep the history)
  if (push.rayPattern == kRtRaysCheckerboard && !tlRtTracesThisFrame(p, frame.frameIndex, push.rayPattern)) {
    // 0.5 rays per pixel: a pixel without a ray this frame takes its horizontal neighbour's
    // sample (which had one) when that neighbour is the same surface, else the vertical one.
    ivec2 a = ivec2(p.x ^ 1, p.y), b = ivec2(p.x, p.y ^ 1);
    a = min(a, size - 1);
    b = min(b, size - 1);
    float da = abs(texelFetch(gDepth, a, 0).r - depth), db = abs(texelFetch(gDepth, b, 0).r - depth);
    src = da <= db ? a : b;
  } else if (push.rayPattern == kRtRaysHalfResolution && !tlRtTracesThisFrame(p, frame.frameIndex, push.rayPattern)) {
    // Half resolution, depth-aware noisy upsampling (INSIDE): of the four traced samples
    // around the pixel (its own 2x2 block and the three towards its side), pick one at random
    // with a probability that falls with the depth difference. The noise averages out in the
    // accumulation below; always taking the nearest would freeze blocks into the image.
    ivec2 own = (p & ~1) + tlRtBlockOffset(frame.frameIndex);
    ivec2 side = ivec2((p.x & 1) == 1 ? 2 : -2, (p.y & 1) == 1 ? 2 : -2);
    ivec2 candidates[4] = ivec2[4](own, own + ivec2(side.x, 0), own + ivec2(0, side.y), own + side);
    float weights[4];
    float total = 0.0;
    for (int i = 0; i < 4; ++i) {
      // Outside the image there is no traced sample (clamping would land on an untraced pixel).
      ivec2 c = candidates[i];
      bool inside = all(greaterThanEqual(c, ivec2(0))) && all(lessThan(c, size));
      float d = inside ? texelFetch(gDepth, c, 0).r : 0.0;
      float rel = abs(d - depth) / max(depth, 1e-6);
      weights[i] = d > 0.0 ? 1.0 / (1e-3 + rel * rel * 1e4) : 0.0;
      total += weights[i];
    }
    if (total <= 0.0) noSample = true;
    // A hash of pixel and frame chooses (uniform in [0, total)).
    float u = tlUintToUnitFloat(tlPcg3d(uvec3(uvec2(p), frame.frameIndex)).x) * total;
    // Rounding may leave u past the last weight: fall back to the heaviest candidate (inside).
    int heaviest = 0;
    for (int i = 1; i < 4; ++i)
      if (weights[i] > weights[heaviest]) heaviest = i;
    src = candidates[heaviest];
    for (int i = 0; i < 4; ++i) {
      if (weights[i] > 0.0 && u < weights[i]) {
        src = candidates[i];
        break;
      }
      u -= weights[i];
    }
  }
  vec4 shY = noSample ? vec4(0.0) : texelFetch(rawShY, src, 0);
  vec4 coCgAo = noSample ? vec4(0.0, 0.0, 1.0, 0.0) : vec4(texelFetch(rawCoCg, src, 0).xy, texelFetch(rawAo, src, 0).r, 1.0);
  if (depth <= 0.0) {
    imageStore(outShY, p, vec4(0.0));
    imageStore(outCoCgAo, p, vec4(0.0, 0.0, 1.0, 0.0));
    imageStore(outDepth, p, vec4(0.0));
    return;
  }
  vec3 position = pixelPosition(p, depth);
  float w = viewW(position);
  if (push.historyValid != 0u) {
    vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
    vec2 previousUv = uv - texelFetch(gMotion, p, 0).xy;
    // Where this surface was last frame, and how far from the camera it was then.
    vec4 previousClip = frame.prevViewProj * vec4(position, 1.0);
    bool onScreen = all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0)));
    if (onScreen && previousClip.w > 0.0) {
      ivec2 q = ivec2(previousUv * frame.viewport.xy);
      float historyW = texelFetch(historyDepth, q, 0).r;
      vec4 history = texelFetch(historyCoCgAo, q, 0);
      bool sameSurface = historyW > 0.0 && abs(historyW - previousClip.w) <= 0.03 * previousClip.w;
      if (sameSurface && history.w >= 1.0 && noSample) {
        shY = texelFetch(historyShY, q, 0);  // nothing new this frame: the history as it was
        coCgAo = history;
      } else if (sameSurface && history.w >= 1.0) {
        float n = min(history.w + 1.0, float(max(push.maxAccumFrames, 1u)));
        float a = 1.0 / n;
        shY = mix(texelFetch(historyShY, q, 0), shY, a);
        coCgAo = vec4(mix(history.xyz, coCgAo.xyz, a), n);
      }
    }
  }
  imageStore(outShY, p, shY);
  imageStore(outCoCgAo, p, coCgAo);
  imageStore(outDepth, p, vec4(w));
}
