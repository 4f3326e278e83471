// The scene's material table and textures (set kSceneSet), and the material inputs every
// stage that sees a surface evaluates the same way: where a texture slot samples (its UV set
// and KHR_texture_transform, shared/scene.h tlSlotUv), the base colour with COLOR_0 multiplied
// in. Fragment stages sample with derivatives (common/material.glsl); ray
// hits and the voxelizer's hit-like reads use the *Lod0 forms (no derivatives there).
#ifndef TL_MATERIAL_DATA_GLSL
#define TL_MATERIAL_DATA_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/scene.h"

layout(set = kSceneSet, binding = kSceneBindingMaterials, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = kSceneSet, binding = kSceneBindingTextures) uniform sampler2D sceneTextures[];

// A slot's texel at the finest level (the caller checks s.texture != kNoTexture).
vec4 slotTexelLod0(GpuTextureSlot s, vec2 uv0, vec2 uv1) {
  return textureLod(sceneTextures[nonuniformEXT(s.texture)], tlSlotUv(s, uv0, uv1), 0.0);
}

// The material inputs, written once for both ways a slot is read: each names its functions and
// the slot reader they sample through. Base colour (linear) and alpha: factor x texture x
// COLOR_0; roughness and metallic (x, y); glTF's occlusion, 1 + strength (texel.r - 1), 1
// without a texture; emission. Below: the *Lod0 forms (slotTexelLod0); common/material.glsl
// makes the fragment forms (sampleSlot, with derivatives). The dielectric's Fresnel: F0 (rgb) and
// F90 (w) from KHR_materials_ior and KHR_materials_specular (shared/scene.h tlDielectricFresnel).
// KHR_materials_transmission's factor x its texture's red; and the coverage the G-buffer paths
// draw a transmitting surface with (shared/scene.h tlTransmissionCoverage; 1: opaque).
#define TL_MATERIAL_INPUTS(BASE_COLOR, ROUGHNESS_METALLIC, OCCLUSION, EMISSION, DIELECTRIC_FRESNEL, TRANSMISSION, COVERAGE, \
                           SAMPLE)                                                                       \
  vec4 BASE_COLOR(GpuMaterial m, vec2 uv0, vec2 uv1, vec4 vertexColor) {                                 \
    vec4 base = m.baseColorFactor * vertexColor;                                                         \
    if (m.baseColorTexture.texture != kNoTexture) base *= SAMPLE(m.baseColorTexture, uv0, uv1);          \
    return base;                                                                                         \
  }                                                                                                      \
  vec2 ROUGHNESS_METALLIC(GpuMaterial m, vec2 uv0, vec2 uv1) {                                           \
    vec2 rm = vec2(m.roughness, m.metallic);                                                             \
    if (m.metallicRoughnessTexture.texture != kNoTexture) rm *= SAMPLE(m.metallicRoughnessTexture, uv0, uv1).gb; \
    return rm;                                                                                           \
  }                                                                                                      \
  float OCCLUSION(GpuMaterial m, vec2 uv0, vec2 uv1) {                                                   \
    if (m.occlusionTexture.texture == kNoTexture) return 1.0;                                            \
    return 1.0 + m.occlusionStrength * (SAMPLE(m.occlusionTexture, uv0, uv1).r - 1.0);                   \
  }                                                                                                      \
  vec3 EMISSION(GpuMaterial m, vec2 uv0, vec2 uv1) {                                                     \
    vec3 e = m.emissive.rgb;                                                                             \
    if (m.emissiveTexture.texture != kNoTexture) e *= SAMPLE(m.emissiveTexture, uv0, uv1).rgb;           \
    return e;                                                                                            \
  }                                                                                                      \
  vec4 DIELECTRIC_FRESNEL(GpuMaterial m, vec2 uv0, vec2 uv1) {                                           \
    vec4 c = m.specularColor;                                                                            \
    if (m.specularTexture.texture != kNoTexture) c.w *= SAMPLE(m.specularTexture, uv0, uv1).a;           \
    if (m.specularColorTexture.texture != kNoTexture) c.rgb *= SAMPLE(m.specularColorTexture, uv0, uv1).rgb; \
    return tlDielectricFresnel(m.ior, c.rgb, c.w);                                                       \
  }                                                                                                      \
  float TRANSMISSION(GpuMaterial m, vec2 uv0, vec2 uv1) {                                                \
    float t = m.transmission;                                                                            \
    if (t > 0.0 && m.transmissionTexture.texture != kNoTexture) t *= SAMPLE(m.transmissionTexture, uv0, uv1).r; \
    return t;                                                                                            \
  }                                                                                                      \
  float COVERAGE(GpuMaterial m, vec2 uv0, vec2 uv1, vec3 baseColor) {                                    \
    if (!(m.transmission > 0.0)) return 1.0;                                                             \
    return tlTransmissionCoverage(TRANSMISSION(m, uv0, uv1), ROUGHNESS_METALLIC(m, uv0, uv1).y, baseColor, \
                                  DIELECTRIC_FRESNEL(m, uv0, uv1).rgb);                                  \
  }

TL_MATERIAL_INPUTS(materialBaseColorLod0, materialRoughnessMetallicLod0, materialOcclusionLod0, materialEmissionLod0,
                   materialDielectricFresnelLod0, materialTransmissionLod0, materialCoverageLod0, slotTexelLod0)

// A normal map's tangent-space texel (as stored, [0, 1]) applied to the unit normal n facing the
// viewer or the ray: the tangent is made orthogonal to n, the bitangent is n x t times the
// handedness (glTF, MikkTSpace), and the texel's xy are scaled by normalTexture.scale. A
// degenerate tangent or a zero result keeps n. Shared by the G-buffer and the reference's hits.
vec3 normalMapped(vec3 n, vec4 tangent, vec3 texel, float scale) {
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  float tl = length(t);
  if (tl <= 1e-6) return n;
  t /= tl;
  vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 tn = texel * 2.0 - 1.0;
  tn.xy *= scale;
  vec3 mapped = t * tn.x + b * tn.y + n * tn.z;
  return dot(mapped, mapped) > 1e-12 ? normalize(mapped) : n;
}

// Alpha testing: true where the surface is cut away (MASK below its cutoff; BLEND where alpha
// does not exceed xi, the stage's stochastic-transparency number in [0, 1)).
bool materialCutout(GpuMaterial m, float alpha, float xi) {
  return tlMaterialCutout(m.alphaMode, m.alphaCutoff, alpha, xi);
}
// The G-buffer paths' test: alpha's, and transmission's coverage (shared/scene.h).
bool materialCutoutTransmitting(GpuMaterial m, float alpha, float coverage, float xi) {
  return tlMaterialCutoutTransmitting(m.alphaMode, m.alphaCutoff, alpha, coverage, xi);
}
#endif
