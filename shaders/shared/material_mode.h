// Material override modes (RenderSettings::materials, `--materials`, docs/accuracy.md): every
// lighting path and the reference shade the scene's surfaces as authored, or all as Lambertian
// (an artist's lighting-only view, and the mode in which Twinlight's images compare exactly
// with any other renderer's). Emission is kept in every mode: lights stay lights.
//   authored  the glTF metal-rough model (shared/shading.h), textures and normal maps
//   diffuse   Lambert with the authored base colour and its texture; no specular, no normal maps
//   clay      Lambert of albedo kClayAlbedo; no textures (a base colour texture's alpha still cuts
//             out, so the geometry is the same), no normal maps
// The mode travels in FrameConstants::flags (shared/frame.h tlFrameMaterials).
#ifndef TL_SHARED_MATERIAL_MODE_H
#define TL_SHARED_MATERIAL_MODE_H
#include "common.h"

TL_BEGIN
TL_CONST uint kMaterialsAuthored = 0u;
TL_CONST uint kMaterialsDiffuse = 1u;
TL_CONST uint kMaterialsClay = 2u;
TL_CONST float kClayAlbedo = 0.8f;

// The surface inputs a mode shades with: base colour (clay replaces it), and a metallic of 0
// and a roughness of 1 in the Lambertian modes (which ignore both, but whatever reads the
// G-buffer then sees the material it shades).
TL_FN vec3 tlMaterialBaseColor(vec3 authored, uint materials) {
  return materials == kMaterialsClay ? vec3(kClayAlbedo) : authored;
}
TL_FN float tlMaterialMetallic(float authored, uint materials) { return materials == kMaterialsAuthored ? authored : 0.0f; }
TL_FN float tlMaterialRoughness(float authored, uint materials) { return materials == kMaterialsAuthored ? authored : 1.0f; }
TL_FN bool tlMaterialNormalMaps(uint materials) { return materials == kMaterialsAuthored; }
// glTF's occlusion texture darkens the indirect light of the authored material only: the
// Lambertian modes are for matching other renderers' diffuse images, which ignore it (as the
// reference does: a path tracer finds the occlusion itself).
TL_FN float tlMaterialOcclusion(float authored, uint materials) { return materials == kMaterialsAuthored ? authored : 1.0f; }
TL_END
#endif
