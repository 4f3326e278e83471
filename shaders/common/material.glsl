// The scene's material table and textures (set kSceneSet), and the inputs every shader that
// shades scene surfaces evaluates the same way: the G-buffer and the albedo baker.
#ifndef TL_MATERIAL_GLSL
#define TL_MATERIAL_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/scene.h"

layout(set = kSceneSet, binding = kSceneBindingMaterials, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = kSceneSet, binding = kSceneBindingTextures) uniform sampler2D sceneTextures[];

// A UV triangle collapsed to one texel (palette atlases) has zero gradients; lavapipe's
// anisotropic filter then returns black, so such texels are read from the finest level.
vec4 sampleTexture(uint index, vec2 uv) {
  vec2 dx = dFdx(uv), dy = dFdy(uv);
  if (dot(dx, dx) + dot(dy, dy) == 0.0) return textureLod(sceneTextures[nonuniformEXT(index)], uv, 0.0);
  return texture(sceneTextures[nonuniformEXT(index)], uv);
}

// Base colour (linear) and alpha.
vec4 materialBaseColor(GpuMaterial m, vec2 uv) {
  vec4 base = m.baseColorFactor;
  if (m.baseColorTexture != kNoTexture) base *= sampleTexture(m.baseColorTexture, uv);
  return base;
}

// Alpha testing: true where the surface is cut away.
bool materialCutout(GpuMaterial m, float alpha) { return tlMaterialCutout(m.alphaCutoff, alpha); }

// x: roughness, y: metallic.
vec2 materialRoughnessMetallic(GpuMaterial m, vec2 uv) {
  vec2 rm = vec2(m.roughness, m.metallic);
  if (m.metallicRoughnessTexture != kNoTexture) rm *= sampleTexture(m.metallicRoughnessTexture, uv).gb;
  return rm;
}
#endif
