#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/reference.h"
#include "shared/scene.h"

layout(set = 0, binding = kRefBindingGeometry, std430) readonly buffer Geometry { RefInstanceGeometry geometry[]; };
layout(set = 0, binding = kRefBindingVertices, std430) readonly buffer Vertices { float vertices[]; };
layout(set = 0, binding = kRefBindingIndices, std430) readonly buffer Indices { uint indices[]; };
layout(set = kSceneSet, binding = kSceneBindingMaterials, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = kSceneSet, binding = kSceneBindingTextures) uniform sampler2D sceneTextures[];

layout(location = 0) rayPayloadInEXT RefHit hit;
hitAttributeEXT vec2 bary;

vec3 attribute3(uint v, uint offset) {
  uint b = v * kVertexFloats + offset;
  return vec3(vertices[b], vertices[b + 1], vertices[b + 2]);
}

void main() {
  uint instance = gl_InstanceCustomIndexEXT;
  RefInstanceGeometry g = geometry[instance];
  GpuInstance inst = instances[instance];
  GpuMaterial m = materials[g.material];
  uint base = g.firstIndex + 3u * uint(gl_PrimitiveID);
  uint v0 = uint(int(indices[base]) + g.vertexOffset);
  uint v1 = uint(int(indices[base + 1]) + g.vertexOffset);
  uint v2 = uint(int(indices[base + 2]) + g.vertexOffset);
  vec3 w = vec3(1.0 - bary.x - bary.y, bary.x, bary.y);

  vec3 p0 = attribute3(v0, 0), p1 = attribute3(v1, 0), p2 = attribute3(v2, 0);
  vec3 n = attribute3(v0, 3) * w.x + attribute3(v1, 3) * w.y + attribute3(v2, 3) * w.z;
  vec2 uv = vec2(vertices[v0 * kVertexFloats + 10], vertices[v0 * kVertexFloats + 11]) * w.x +
            vec2(vertices[v1 * kVertexFloats + 10], vertices[v1 * kVertexFloats + 11]) * w.y +
            vec2(vertices[v2 * kVertexFloats + 10], vertices[v2 * kVertexFloats + 11]) * w.z;
  mat3 normalMatrix = mat3(inst.normalMatrix);
  vec3 geometric = normalize(normalMatrix * cross(p1 - p0, p2 - p0));
  vec3 shading = normalize(normalMatrix * n);
  // Surfaces are two-sided: both normals face the incoming ray.
  if (dot(geometric, gl_WorldRayDirectionEXT) > 0.0) geometric = -geometric;
  if (dot(shading, geometric) < 0.0) shading = -shading;

  vec4 baseColor = m.baseColorFactor;
  if (m.baseColorTexture != kNoTexture) baseColor *= textureLod(sceneTextures[nonuniformEXT(m.baseColorTexture)], uv, 0.0);
  float roughness = m.roughness, metallic = m.metallic;
  if (m.metallicRoughnessTexture != kNoTexture) {
    vec4 mr = textureLod(sceneTextures[nonuniformEXT(m.metallicRoughnessTexture)], uv, 0.0);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  vec3 emission = m.emissive.rgb;
  if (m.emissiveTexture != kNoTexture) emission *= textureLod(sceneTextures[nonuniformEXT(m.emissiveTexture)], uv, 0.0).rgb;

  // Position from the triangle, not origin + t * direction: exact at any distance.
  vec3 position = vec3(inst.modelRelative * vec4(p0 * w.x + p1 * w.y + p2 * w.z, 1.0));
  hit.positionT = vec4(position, gl_HitTEXT);
  hit.normal = vec4(shading, 0.0);
  hit.geometric = vec4(geometric, 0.0);
  hit.baseColor = vec4(clamp(baseColor.rgb, 0.0, 1.0), clamp(roughness, 0.0, 1.0));
  hit.emission = vec4(emission, clamp(metallic, 0.0, 1.0));
}
