// Material inputs for fragment stages (G-buffer, shadow map, voxelizer, albedo baker):
// common/material_data.glsl's, sampled with the fragment's derivatives.
#ifndef TL_MATERIAL_GLSL
#define TL_MATERIAL_GLSL
#include "common/material_data.glsl"

// A UV triangle collapsed to one texel (palette atlases) has zero gradients; lavapipe's
// anisotropic filter then returns black, so such texels are read from the finest level.
vec4 sampleSlot(GpuTextureSlot s, vec2 uv0, vec2 uv1) {
  vec2 uv = tlSlotUv(s, uv0, uv1);
  vec2 dx = dFdx(uv), dy = dFdy(uv);
  if (dot(dx, dx) + dot(dy, dy) == 0.0) return textureLod(sceneTextures[nonuniformEXT(s.texture)], uv, 0.0);
  return texture(sceneTextures[nonuniformEXT(s.texture)], uv);
}

// Base colour (linear) and alpha: factor x texture x COLOR_0.
vec4 materialBaseColor(GpuMaterial m, vec2 uv0, vec2 uv1, vec4 vertexColor) {
  vec4 base = m.baseColorFactor * vertexColor;
  if (m.baseColorTexture.texture != kNoTexture) base *= sampleSlot(m.baseColorTexture, uv0, uv1);
  return base;
}

// x: roughness, y: metallic.
vec2 materialRoughnessMetallic(GpuMaterial m, vec2 uv0, vec2 uv1) {
  vec2 rm = vec2(m.roughness, m.metallic);
  if (m.metallicRoughnessTexture.texture != kNoTexture) rm *= sampleSlot(m.metallicRoughnessTexture, uv0, uv1).gb;
  return rm;
}

// glTF's occlusion: 1 + strength (texel.r - 1); 1 without a texture.
float materialOcclusion(GpuMaterial m, vec2 uv0, vec2 uv1) {
  if (m.occlusionTexture.texture == kNoTexture) return 1.0;
  return 1.0 + m.occlusionStrength * (sampleSlot(m.occlusionTexture, uv0, uv1).r - 1.0);
}

vec3 materialEmission(GpuMaterial m, vec2 uv0, vec2 uv1) {
  vec3 e = m.emissive.rgb;
  if (m.emissiveTexture.texture != kNoTexture) e *= sampleSlot(m.emissiveTexture, uv0, uv1).rgb;
  return e;
}
#endif
