#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/frame.h"
#include "shared/reference.h"
#include "shared/scene.h"
#include "reference/hit_vertices.glsl"

layout(set = 0, binding = kRefBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

layout(location = 0) rayPayloadInEXT RefHit hit;
hitAttributeEXT vec2 bary;

void main() {
  uint instance = gl_InstanceCustomIndexEXT;
  RefInstanceGeometry g = geometry[instance];
  GpuInstance inst = instances[instance];
  GpuMaterial m = materials[g.material];
  RefHitVertices h = refHitVertices(g, uint(gl_PrimitiveID), bary);

  mat3 normalMatrix = mat3(inst.normalMatrix);
  vec3 geometric = normalize(normalMatrix * cross(h.p1 - h.p0, h.p2 - h.p0));
  vec3 shading = normalize(normalMatrix * h.normal);
  // Both normals face the incoming ray. The normal matrix keeps the object-space front where
  // glTF puts it, mirrored instances included (shared/scene.h): seen from behind, a
  // single-sided surface is reported so that camera rays pass it (path.glsl).
  bool back = dot(geometric, gl_WorldRayDirectionEXT) > 0.0;
  if (back) geometric = -geometric;
  if (dot(shading, geometric) < 0.0) shading = -shading;
  // The normal map as the G-buffer applies it (material_data.glsl), on the side the ray sees;
  // the tangent is a surface direction: the model matrix carries it, not the normal matrix.
  if (m.normalTexture.texture != kNoTexture && tlMaterialNormalMaps(tlFrameMaterials(frame.flags))) {
    vec4 tangent = vec4(mat3(inst.modelRelative) * h.tangent.xyz, h.tangent.w);
    shading = normalMapped(shading, tangent, slotTexelLod0(m.normalTexture, h.uv0, h.uv1).xyz, m.normalScale);
  }

  vec4 baseColor = materialBaseColorLod0(m, h.uv0, h.uv1, h.color);
  vec2 rm = materialRoughnessMetallicLod0(m, h.uv0, h.uv1);
  vec3 emission = materialEmissionLod0(m, h.uv0, h.uv1);
  vec4 fresnel = materialDielectricFresnelLod0(m, h.uv0, h.uv1);
  // Unlit (shared/scene.h): the base colour as emission over a black surface with no specular,
  // as the G-buffer writes it. The override modes' clay replaces its colour there too.
  if ((m.flags & kMaterialUnlit) != 0u) {
    emission += clamp(tlMaterialBaseColor(baseColor.rgb, tlFrameMaterials(frame.flags)), 0.0, 1.0);
    baseColor.rgb = vec3(0.0);
    fresnel = vec4(0.0);
  }

  // Position from the triangle, not origin + t * direction: exact at any distance.
  vec3 w = vec3(1.0 - bary.x - bary.y, bary.x, bary.y);
  vec3 position = vec3(inst.modelRelative * vec4(h.p0 * w.x + h.p1 * w.y + h.p2 * w.z, 1.0));
  hit.positionT = vec4(position, gl_HitTEXT);
  // A volume's boundary is seen from inside by the rays it refracts in: never culled.
  bool culled = back && tlMaterialCulledFromBehind(m.flags) && !(m.thickness > 0.0 && m.transmission > 0.0);
  hit.normal = vec4(shading, culled ? 1.0 : 0.0);
  hit.geometric = vec4(geometric, refEmitterDensity(g, uint(gl_PrimitiveID), refWorldArea(inst.modelRelative, h)));
  hit.baseColor = vec4(clamp(baseColor.rgb, 0.0, 1.0), clamp(rm.x, 0.0, 1.0));
  hit.emission = vec4(emission, clamp(rm.y, 0.0, 1.0));
  hit.fresnel = fresnel;
  hit.transmission = vec4(materialTransmissionLod0(m, h.uv0, h.uv1), m.thickness > 0.0 ? 1.0 : 0.0, back ? 1.0 : 0.0, m.ior);
  hit.absorption = m.thickness > 0.0 ? m.absorption : vec4(0.0);
  hit.coat = vec4(m.clearcoat, m.clearcoatRoughness, 0.0, 0.0);
}
