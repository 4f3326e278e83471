#version 460
// Full resolution from the reduced-resolution SSAO and cone tracing: for each, a depth-aware
// filter over the 2x2 reduced texels around the pixel (for the SSAO this also averages its
// 2x2 rotation pattern). AO = SSAO x voxel AO. The SSAO then accumulates over frames
// (its directions turn each frame): reprojected with the motion vectors, history rejected off
// screen or on another surface (view-depth test), weight 1/n up to aoHistory frames.
#extension GL_GOOGLE_include_directive : require
#include "legacy/legacy_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingAoRaw) uniform sampler2D aoRaw;
layout(set = 0, binding = kLegacyBindingConeShY) uniform sampler2D coneShY;
layout(set = 0, binding = kLegacyBindingConeCoCgAo) uniform sampler2D coneCoCgAo;
layout(set = 0, binding = kLegacyBindingOutAo, r16f) uniform writeonly image2D aoOut;
layout(set = 0, binding = kLegacyBindingAoHistory) uniform sampler2D aoHistory;
layout(set = 0, binding = kLegacyBindingSsaoOut, rg16f) uniform writeonly image2D ssaoOut;
layout(set = 0, binding = kLegacyBindingPrevDepth) uniform sampler2D previousDepth;
layout(set = 0, binding = kLegacyBindingMotion) uniform sampler2D gMotion;
layout(set = 0, binding = kLegacyBindingOutShY, rgba16f) uniform writeonly image2D shYOut;
layout(set = 0, binding = kLegacyBindingOutCoCg, rg16f) uniform writeonly image2D coCgOut;

float w0;
ivec2 size;

// Weight of a reduced texel from the view depth it stored (0: sky).
float depthWeight(float w) {
  if (w <= 0.0) return 0.0;
  float rel = abs(w - w0) / (0.02 * w0);
  return 1.0 / (1.0 + rel * rel);
}

// The 2x2 reduced texels whose footprints' centres surround pixel p; at the borders the
// nearest 2x2 inside, so every pixel still averages four different texels (four SSAO rotations).
ivec2 tapBase(ivec2 p, uint d) {
  if (d == 1u) return p;
  ivec2 base = ivec2(floor((vec2(p) + 0.5) / float(d) - 0.5));
  return clamp(base, ivec2(0), max(reducedSize(d) - 2, ivec2(0)));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(aoOut, p, vec4(1.0));
    imageStore(ssaoOut, p, vec4(1.0, 0.0, 0.0, 0.0));
    imageStore(shYOut, p, vec4(0.0));
    imageStore(coCgOut, p, vec4(0.0));
    return;
  }
  w0 = depthToViewW(depth);

  float ao = 0.0, aoWeight = 0.0;
  ivec2 aoBase = tapBase(p, push.aoDivisor), aoMax = reducedSize(push.aoDivisor) - 1;
  int aoTaps = push.aoDivisor == 1u ? 1 : 2;
  for (int y = 0; y < aoTaps; ++y)
    for (int x = 0; x < aoTaps; ++x) {
      ivec2 q = clamp(aoBase + ivec2(x, y), ivec2(0), aoMax);
      vec2 raw = texelFetch(aoRaw, q, 0).rg;
      float k = depthWeight(raw.g);
      ao += k * raw.r;
      aoWeight += k;
    }

  vec4 shY = vec4(0.0), coCgAo = vec4(0.0);
  float giWeight = 0.0;
  ivec2 giBase = tapBase(p, push.coneDivisor), giMax = reducedSize(push.coneDivisor) - 1;
  int giTaps = push.coneDivisor == 1u ? 1 : 2;
  for (int y = 0; y < giTaps; ++y)
    for (int x = 0; x < giTaps; ++x) {
      ivec2 q = clamp(giBase + ivec2(x, y), ivec2(0), giMax);
      vec4 cone = texelFetch(coneCoCgAo, q, 0);
      float k = depthWeight(cone.w);
      shY += k * texelFetch(coneShY, q, 0);
      coCgAo += k * cone;
      giWeight += k;
    }
  float ssao = aoWeight > 0.0 ? clamp(ao / aoWeight, 0.0, 1.0) : 1.0;
  float frames = 1.0;
  if (push.aoHistory > 0u) {
    vec2 previousUv = (vec2(p) + 0.5) * frame.viewport.zw - texelFetch(gMotion, p, 0).xy;
    vec4 previousClip = frame.prevViewProj * vec4(pixelPosition(p, depth), 1.0);
    if (all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0))) && previousClip.w > 0.0) {
      ivec2 q = ivec2(previousUv * frame.viewport.xy);
      float previous = texelFetch(previousDepth, q, 0).r;
      vec2 history = texelFetch(aoHistory, q, 0).rg;
      if (previous > 0.0 && abs(depthToViewW(previous) - previousClip.w) <= 0.03 * previousClip.w && history.g >= 1.0) {
        frames = min(history.g + 1.0, float(push.aoHistory));
        ssao = mix(history.r, ssao, 1.0 / frames);
      }
    }
  }
  float vxao = giWeight > 0.0 ? coCgAo.z / giWeight : 1.0;
  imageStore(aoOut, p, vec4(ssao * vxao));
  imageStore(ssaoOut, p, vec4(ssao, frames, 0.0, 0.0));
  imageStore(shYOut, p, giWeight > 0.0 ? shY / giWeight : vec4(0.0));
  imageStore(coCgOut, p, vec4(giWeight > 0.0 ? coCgAo.xy / giWeight : vec2(0.0), 0.0, 0.0));
}
