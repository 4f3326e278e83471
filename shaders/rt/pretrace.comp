#version 460
// Screen-space pre-trace (Metro Exodus): the exact ray of the real trace, marched against
// the depth buffer over a roughly constant screen length. Where it finds a surface, hit
// distance, albedo, normal and emission come from the G-buffer and no real ray is traced
// (the albedo scaled by the instance's albedo-database correction, shared/rt.h RtInstance).
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtBindingEmissive) uniform sampler2D gEmissive;
layout(set = 0, binding = kRtBindingInstanceId) uniform usampler2D gInstanceId;
layout(set = 0, binding = kRtBindingInstances, std430) readonly buffer Instances { RtInstance rtInstances[]; };
layout(set = 0, binding = kRtBindingHitsOut, r32ui) uniform writeonly uimage2D hitsOut;
layout(set = 0, binding = kRtBindingSurfaceOut, rg32ui) uniform writeonly uimage2D surfaceOut;

void main() {
  ivec2 p = tracedPixel(ivec2(gl_GlobalInvocationID.xy));
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // sky: no surface, no ray
    imageStore(hitsOut, p, uvec4(kRtHitMiss));
    imageStore(surfaceOut, p, uvec4(0u));
    return;
  }
  vec3 position = pixelPosition(p, depth);
  vec3 n = pixelNormal(p);
  vec3 dir = pixelRayDirection(p, n);
  uint result = kRtHitPending;
  uvec2 surface = uvec2(0u);
  if (push.pretrace != 0u) {
    // A roughly constant screen length: pixels times the world size of a pixel here.
    float rayLength = min(push.pretraceLength * pixelFootprint(viewW(position)), push.tMax);
    uint steps = max(push.pretraceSteps, 1u);
    // A per-pixel offset of the samples (from the same noise) hides the step pattern.
    float jitter = fract(dot(vec2(p), vec2(0.7548777, 0.5698403)) + float(frame.frameIndex & 63u) * 0.618034);
    float previousT = 0.0;
    for (uint i = 0u; i < steps; ++i) {
      float t = rayLength * (float(i) + jitter + 1.0) / float(steps + 1u);
      vec3 q = position + dir * t;
      vec4 clip = frame.viewProj * vec4(q, 1.0);
      if (clip.w <= 1e-6) break;
      vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
      if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) break;
      ivec2 s = ivec2(uv * frame.viewport.xy);
      if (s == p) continue;  // still on the starting pixel
      float sceneDepth = texelFetch(gDepth, s, 0).r;
      if (sceneDepth <= 0.0) continue;
      vec3 scenePosition = pixelPosition(s, sceneDepth);
      float sceneW = viewW(scenePosition);
      float behind = viewWOfClip(clip) - sceneW;
      if (behind > 0.0) {
        // Behind a surface thicker than `thickness` of its distance: hidden, not hit.
        if (behind > push.thickness * sceneW + (t - previousT)) break;
        vec3 sn = pixelNormal(s);
        if (dot(sn, dir) >= 0.0) break;  // the back of something: let a real ray decide
        // The ray meets the depth-buffer surface's plane: exact distance for planar surfaces.
        float denom = dot(sn, dir);
        float tPlane = dot(sn, scenePosition - position) / denom;
        float distance = clamp(tPlane, previousT, t);
        vec3 base = texelFetch(gBaseColor, s, 0).rgb;
        float metallic = texelFetch(gMaterial, s, 0).g;
        // The G-buffer's albedo, scaled as the instance's database entry or override asks.
        uint id = texelFetch(gInstanceId, s, 0).r;
        vec3 scale = id > 0u ? rtInstances[id - 1u].albedoScale.rgb : vec3(1.0);
        vec3 albedo = tlMaterialHitAlbedo(base, metallic, tlFrameMaterials(frame.flags));
        result = tlRtPackHit(distance, clamp(albedo * scale, 0.0, 1.0));
        surface = uvec2(tlOctEncodeSnorm16(sn), tlPackRgb9e5(texelFetch(gEmissive, s, 0).rgb));
        break;
      }
      previousT = t;
    }
  }
  imageStore(hitsOut, p, uvec4(result));
  imageStore(surfaceOut, p, uvec4(surface, 0u, 0u));
}
