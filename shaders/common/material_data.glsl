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

// Base colour (linear) and alpha: factor x texture x COLOR_0.
vec4 materialBaseColorLod0(GpuMaterial m, vec2 uv0, vec2 uv1, vec4 vertexColor) {
  vec4 base = m.baseColorFactor * vertexColor;
  if (m.baseColorTexture.texture != kNoTexture) base *= slotTexelLod0(m.baseColorTexture, uv0, uv1);
  return base;
}

// x: roughness, y: metallic.
vec2 materialRoughnessMetallicLod0(GpuMaterial m, vec2 uv0, vec2 uv1) {
  vec2 rm = vec2(m.roughness, m.metallic);
  if (m.metallicRoughnessTexture.texture != kNoTexture) rm *= slotTexelLod0(m.metallicRoughnessTexture, uv0, uv1).gb;
  return rm;
}

vec3 materialEmissionLod0(GpuMaterial m, vec2 uv0, vec2 uv1) {
  vec3 e = m.emissive.rgb;
  if (m.emissiveTexture.texture != kNoTexture) e *= slotTexelLod0(m.emissiveTexture, uv0, uv1).rgb;
  return e;
}

// Alpha testing: true where the surface is cut away (MASK below its cutoff; BLEND where alpha
// does not exceed xi, the stage's stochastic-transparency number in [0, 1)).
bool materialCutout(GpuMaterial m, float alpha, float xi) {
  return tlMaterialCutout(m.alphaMode, m.alphaCutoff, alpha, xi);
}
#endif
