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

TL_MATERIAL_INPUTS(materialBaseColor, materialRoughnessMetallic, materialOcclusion, materialEmission,
                   materialDielectricFresnel, materialTransmission, materialCoverage, sampleSlot)
#endif
