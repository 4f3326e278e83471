#version 460
// Closest hit: pack distance and the instance's pre-filtered albedo into the payload; the
// geometric normal (facing the ray) and the emission go to the hit-surface image, which
// hit lighting needs for the sun's cosine and emitters.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "rt/rt_common.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Indices { uint i[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Vertices { float f[]; };
layout(set = 0, binding = kRtBindingInstances, std430) readonly buffer Instances { RtInstance rtInstances[]; };
layout(set = 0, binding = kRtBindingSurfaceOut, rg32ui) uniform writeonly uimage2D surfaceOut;

layout(location = 0) rayPayloadInEXT uint hitRecord;

const uint kVertexFloats = 12u;  // tl::scene::Vertex

vec3 vertexPosition(Vertices v, uint index) {
  uint b = index * kVertexFloats;
  return vec3(v.f[b], v.f[b + 1u], v.f[b + 2u]);
}

void main() {
  RtInstance inst = rtInstances[gl_InstanceCustomIndexEXT];
  Indices indices = Indices(inst.indexAddress);
  Vertices vertices = Vertices(inst.vertexAddress);
  uint base = 3u * uint(gl_PrimitiveID);
  vec3 p0 = vertexPosition(vertices, indices.i[base]);
  vec3 p1 = vertexPosition(vertices, indices.i[base + 1u]);
  vec3 p2 = vertexPosition(vertices, indices.i[base + 2u]);
  // Object -> world normals use the inverse transpose: n * WorldToObject.
  vec3 n = normalize(vec4(cross(p1 - p0, p2 - p0), 0.0) * mat4(gl_WorldToObjectEXT)).xyz;
  if (dot(n, gl_WorldRayDirectionEXT) > 0.0) n = -n;
  hitRecord = tlRtPackHit(gl_HitTEXT, inst.albedo.rgb);
  // The pixel, not the launch index: with 0.5 rays per pixel they differ.
  imageStore(surfaceOut, tracedPixel(ivec2(gl_LaunchIDEXT.xy)), uvec4(tlOctEncodeSnorm16(n), tlPackRgb9e5(inst.emission.rgb), 0u, 0u));
}
