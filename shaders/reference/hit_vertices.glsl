// The reference's view of a hit triangle: its three vertices fetched from the scene's vertex
// buffer and the attributes interpolated at the hit's barycentrics. Shared by the closest-hit
// (shading) and the any-hit (alpha cut-out) shaders, so both read the same UVs and colours.
#ifndef TL_REF_HIT_VERTICES_GLSL
#define TL_REF_HIT_VERTICES_GLSL
#include "shared/emitters.h"
#include "shared/reference.h"
#include "common/material_data.glsl"

layout(set = 0, binding = kRefBindingGeometry, std430) readonly buffer Geometry { RefInstanceGeometry geometry[]; };
layout(set = 0, binding = kRefBindingVertices, std430) readonly buffer Vertices { float vertices[]; };
layout(set = 0, binding = kRefBindingIndices, std430) readonly buffer Indices { uint indices[]; };

struct RefHitVertices {
  vec3 p0, p1, p2;  // object space
  vec3 normal;      // interpolated, object space, not normalized
  vec4 tangent;     // interpolated xyz (object space), handedness of the first vertex in w
  vec2 uv0, uv1;
  vec4 color;
};

vec2 refVertex2(uint v, uint at) { return vec2(vertices[v * kVertexFloats + at], vertices[v * kVertexFloats + at + 1u]); }
vec3 refVertex3(uint v, uint at) {
  uint b = v * kVertexFloats + at;
  return vec3(vertices[b], vertices[b + 1u], vertices[b + 2u]);
}
vec4 refVertex4(uint v, uint at) {
  uint b = v * kVertexFloats + at;
  return vec4(vertices[b], vertices[b + 1u], vertices[b + 2u], vertices[b + 3u]);
}

RefHitVertices refHitVertices(RefInstanceGeometry g, uint primitive, vec2 bary) {
  uint base = g.firstIndex + 3u * primitive;
  uint v[3];
  for (uint k = 0u; k < 3u; ++k) v[k] = uint(int(indices[base + k]) + g.vertexOffset);
  vec3 w = vec3(1.0 - bary.x - bary.y, bary.x, bary.y);
  RefHitVertices h;
  h.p0 = refVertex3(v[0], kVertexPosition);
  h.p1 = refVertex3(v[1], kVertexPosition);
  h.p2 = refVertex3(v[2], kVertexPosition);
  h.normal = vec3(0.0);
  h.tangent = vec4(0.0, 0.0, 0.0, refVertex4(v[0], kVertexTangent).w);
  h.uv0 = h.uv1 = vec2(0.0);
  h.color = vec4(0.0);
  for (uint k = 0u; k < 3u; ++k) {
    h.normal += refVertex3(v[k], kVertexNormal) * w[k];
    h.tangent.xyz += refVertex3(v[k], kVertexTangent) * w[k];
    h.uv0 += refVertex2(v[k], kVertexUv) * w[k];
    h.uv1 += refVertex2(v[k], kVertexUv1) * w[k];
    h.color += refVertex4(v[k], kVertexColor) * w[k];
  }
  return h;
}
// The reference's emitter table (shared/emitters.h), bound where the scene has emitters: the
// closest hit reads the probability of the triangle it hit, the paths draw from it.
layout(set = 0, binding = kRefBindingEmitters, std430) readonly buffer Emitters { Emitter emitters[]; };

// The area of a triangle in camera-relative world space (its instance's transform): the area
// emitter sampling spreads a triangle's probability over, the same at a draw and at a hit.
float refWorldArea(mat4 modelRelative, RefHitVertices h) {
  mat3 m = mat3(modelRelative);
  return 0.5 * length(cross(m * (h.p1 - h.p0), m * (h.p2 - h.p0)));
}

// The density per unit area with which emitter sampling draws a point of triangle `primitive`
// of an instance with geometry g: its entry's probability over its area; 0 off the table.
float refEmitterDensity(RefInstanceGeometry g, uint primitive, float area) {
  if (g.emitters == 0u || !(area > 0.0)) return 0.0;
  return emitters[g.emitters - 1u + primitive].edge2.w / area;
}
#endif
