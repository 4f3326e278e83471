// What a closest-hit shader knows of its hit beyond the distance: the triangle's geometric
// normal turned to face the ray (the sun's cosine at the hit) and the instance's emission.
// Shared by rt/trace.rchit and rt/disocclusion.rchit. Include after rt/rt_common.glsl.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Indices { uint i[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Vertices { float f[]; };
layout(set = 0, binding = kRtBindingInstances, std430) readonly buffer Instances { RtInstance rtInstances[]; };
#include "shared/scene.h"

vec3 vertexPosition(Vertices v, uint index) {
  uint b = index * kVertexFloats;
  return vec3(v.f[b], v.f[b + 1u], v.f[b + 2u]);
}

// The hit triangle's world normal, facing against the ray.
vec3 hitFacingNormal(RtInstance inst) {
  Indices indices = Indices(inst.indexAddress);
  Vertices vertices = Vertices(inst.vertexAddress);
  uint base = 3u * uint(gl_PrimitiveID);
  vec3 p0 = vertexPosition(vertices, indices.i[base]);
  vec3 p1 = vertexPosition(vertices, indices.i[base + 1u]);
  vec3 p2 = vertexPosition(vertices, indices.i[base + 2u]);
  // Object -> world normals use the inverse transpose: n * WorldToObject.
  vec3 n = normalize(vec4(cross(p1 - p0, p2 - p0), 0.0) * mat4(gl_WorldToObjectEXT)).xyz;
  return dot(n, gl_WorldRayDirectionEXT) > 0.0 ? -n : n;
}
