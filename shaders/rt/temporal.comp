#version 460
// Temporal accumulation of the RT path's raw SH irradiance and AO, before any spatial
// filtering (Metro Exodus): reproject with the motion vectors, reject history that falls
// off screen or belongs to another surface (view-depth test), and average with weight
// 1 / n, n growing to maxAccumFrames. Linear space throughout.
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"

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
  // 0.5 rays per pixel: a pixel without a ray this frame takes its horizontal neighbour's
  // sample (which had one) when that neighbour is the same surface, else the vertical one.
  ivec2 src = p;
  if (!tlRtTracesThisFrame(p, frame.frameIndex, push.halfRays)) {
    ivec2 a = ivec2(p.x ^ 1, p.y), b = ivec2(p.x, p.y ^ 1);
    a = min(a, size - 1);
    b = min(b, size - 1);
    float da = abs(texelFetch(gDepth, a, 0).r - depth), db = abs(texelFetch(gDepth, b, 0).r - depth);
    src = da <= db ? a : b;
  }
  vec4 shY = texelFetch(rawShY, src, 0);
  vec4 coCgAo = vec4(texelFetch(rawCoCg, src, 0).xy, texelFetch(rawAo, src, 0).r, 1.0);
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
      if (sameSurface && history.w >= 1.0) {
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
