#version 460
// The SSAO's temporal accumulation, at the SSAO's own (reduced) resolution and before the
// upsample: a quarter of the pixels of doing it after. Each texel's directions turn each
// frame, so accumulating its own history gathers new directions while the camera holds still.
// Reprojected with the motion vectors of the full-resolution pixel the texel stands for;
// history rejected off screen or on another surface (the view depth the history texel stored
// against this point's depth in the last frame), weight 1/n up to aoHistory frames.
#extension GL_GOOGLE_include_directive : require
#include "legacy/legacy_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingAoRaw) uniform sampler2D aoRaw;           // AO, view depth
layout(set = 0, binding = kLegacyBindingAoHistory) uniform sampler2D aoHistory;   // AO, view depth, frames
layout(set = 0, binding = kLegacyBindingMotion) uniform sampler2D gMotion;
layout(set = 0, binding = kLegacyBindingSsaoOut, rgba16f) uniform writeonly image2D ssaoOut;  // AO, view depth, frames

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 reduced = reducedSize(push.aoDivisor);
  if (any(greaterThanEqual(q, reduced))) return;
  vec2 raw = texelFetch(aoRaw, q, 0).rg;
  if (raw.g <= 0.0) {  // sky: no surface, no history
    imageStore(ssaoOut, q, vec4(1.0, 0.0, 0.0, 0.0));
    return;
  }
  ivec2 p = fullPixel(q, push.aoDivisor);
  float ao = raw.r;
  float frames = 1.0;
  if (push.aoHistory > 0u) {
    vec2 previousUv = (vec2(p) + 0.5) * frame.viewport.zw - texelFetch(gMotion, p, 0).xy;
    vec4 previousClip = frame.prevViewProj * vec4(pixelPosition(p, texelFetch(gDepth, p, 0).r), 1.0);
    if (all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0))) && previousClip.w > 0.0) {
      // The history texel whose full-resolution pixel lies nearest the reprojected point.
      vec2 previousPixel = previousUv * frame.viewport.xy - 0.5;
      ivec2 h = clamp(ivec2(round(previousPixel / float(push.aoDivisor))), ivec2(0), reduced - 1);
      vec3 history = texelFetch(aoHistory, h, 0).rgb;
      float previousW = viewWOfClip(previousClip);
      if (history.g > 0.0 && abs(history.g - previousW) <= 0.03 * previousW && history.b >= 1.0) {
        frames = min(history.b + 1.0, float(push.aoHistory));
        ao = mix(history.r, ao, 1.0 / frames);
      }
    }
  }
  imageStore(ssaoOut, q, vec4(clamp(ao, 0.0, 1.0), raw.g, frames, 0.0));
}
