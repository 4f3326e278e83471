#version 460
// Closest hit of a disocclusion ray: the whole hit in the payload (record, facing normal,
// emission), since many rays of one launch share no per-ray image.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "rt/rt_common.glsl"
#include "rt/hit_surface.glsl"

layout(location = 0) rayPayloadInEXT uvec3 hitPayload;  // record, oct normal, rgb9e5 emission

void main() {
  RtInstance inst = rtInstances[gl_InstanceCustomIndexEXT];
  hitPayload = uvec3(tlRtPackHit(gl_HitTEXT, inst.albedo.rgb), tlOctEncodeSnorm16(hitFacingNormal(inst)),
                     tlPackRgb9e5(inst.emission.rgb));
}
