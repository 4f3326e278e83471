#version 460
// Closest hit: pack distance and the instance's pre-filtered albedo into the payload; the
// geometric normal (facing the ray) and the emission go to the hit-surface image, which
// hit lighting needs for the sun's cosine and emitters.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "rt/rt_common.glsl"
#include "rt/hit_surface.glsl"

layout(set = 0, binding = kRtBindingSurfaceOut, rg32ui) uniform writeonly uimage2D surfaceOut;

layout(location = 0) rayPayloadInEXT uint hitRecord;

void main() {
  RtInstance inst = rtInstances[gl_InstanceCustomIndexEXT];
  hitRecord = tlRtPackHit(gl_HitTEXT, inst.albedo.rgb);
  // The pixel, not the launch index: with 0.5 rays per pixel they differ.
  imageStore(surfaceOut, tracedPixel(ivec2(gl_LaunchIDEXT.xy)),
             uvec4(tlOctEncodeSnorm16(hitFacingNormal(inst)), tlPackRgb9e5(inst.emission.rgb), 0u, 0u));
}
