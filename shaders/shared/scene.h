// Scene data shared by the importer/uploader (C++) and the shaders (GLSL).
#ifndef TL_SHARED_SCENE_H
#define TL_SHARED_SCENE_H
#include "common.h"

TL_BEGIN
// Vertex attribute locations of the one interleaved vertex format (position, normal,
// tangent with handedness in w, TEXCOORD_0, TEXCOORD_1, COLOR_0); the C++ struct is
// tl::scene::Vertex.
TL_CONST uint kAttrPosition = 0;
TL_CONST uint kAttrNormal = 1;
TL_CONST uint kAttrTangent = 2;
TL_CONST uint kAttrUv = 3;
TL_CONST uint kAttrUv1 = 4;
TL_CONST uint kAttrColor = 5;

// The same vertex as floats, for shaders that fetch vertices from a storage buffer (ray hits,
// the voxelizer): its size and where each attribute starts.
TL_CONST uint kVertexFloats = 18;
TL_CONST uint kVertexPosition = 0;
TL_CONST uint kVertexNormal = 3;
TL_CONST uint kVertexTangent = 6;
TL_CONST uint kVertexUv = 10;
TL_CONST uint kVertexUv1 = 12;
TL_CONST uint kVertexColor = 14;

TL_CONST uint kNoTexture = 0xFFFFFFFFu;

// The scene's descriptor set (a gpu::DescriptorTable), bound as set 1 where scene
// materials are shaded. The texture table is last: a partially bound array.
TL_CONST uint kSceneSet = 1;
TL_CONST uint kSceneBindingMaterials = 0;
TL_CONST uint kSceneBindingInstances = 1;
TL_CONST uint kSceneBindingTextures = 2;
TL_CONST uint kSceneMaxTextures = 1024;

// One texture a material reads (a glTF textureInfo): which entry of the texture array (its
// sampler comes with it), which UV set, and the KHR_texture_transform as one affine map
// uv' = L uv + offset, L = translation-free part of T * R * S (shared by every stage).
struct GpuTextureSlot {
  vec4 linear;     // L's columns: (linear.x, linear.y) and (linear.z, linear.w)
  vec2 offset;
  uint texture;    // kNoTexture: none
  uint texCoord;   // 0: TEXCOORD_0, 1: TEXCOORD_1
};

// One material, std430. Texture slots index the scene's texture array (kNoTexture: none).
struct GpuMaterial {
  vec4 baseColorFactor;     // linear RGB + alpha
  vec4 emissive;            // linear RGB radiance scale (factor * strength), w unused
  float metallic;
  float roughness;
  float normalScale;
  float alphaCutoff;        // alpha MASK's cutoff (tlMaterialCutout)
  float occlusionStrength;  // glTF occlusionTexture.strength: occlusion = 1 + strength (texel.r - 1)
  uint alphaMode;           // kAlphaOpaque, kAlphaMask or kAlphaBlend
  uint flags;               // kMaterialDoubleSided, kMaterialUnlit
  float ior;                // KHR_materials_ior (1.5 without it; 0: Fresnel 1)
  vec4 specularColor;       // KHR_materials_specular: rgb specularColorFactor, w specularFactor (1, 1 without it)
  GpuTextureSlot baseColorTexture;
  GpuTextureSlot normalTexture;
  GpuTextureSlot metallicRoughnessTexture;
  GpuTextureSlot emissiveTexture;
  GpuTextureSlot occlusionTexture;
  GpuTextureSlot specularTexture;       // KHR_materials_specular: its alpha scales specularFactor
  GpuTextureSlot specularColorTexture;  // and its rgb (sRGB) specularColorFactor
  float transmission;                   // KHR_materials_transmission's factor (shared/shading.h tlSurfaceTransmitting)
  float thickness;                      // KHR_materials_volume's thicknessFactor: above 0 the mesh bounds a volume
  float clearcoat;                      // KHR_materials_clearcoat's factor (0: none; shared/shading.h tlSurfaceCoated)
  float clearcoatRoughness;             // and its roughness factor
  vec4 absorption;                     // KHR_materials_volume: rgb the absorption coefficient per scene unit,
                                       // -ln(attenuationColor) / attenuationDistance (0: clear)
  GpuTextureSlot transmissionTexture;  // KHR_materials_transmission: its red scales the factor
};

// glTF's doubleSided. A single-sided surface (the flag clear) is culled where the camera sees
// its back: the G-buffer discards it and the reference's camera rays pass through it. Every
// other view of it (shadow maps, shadow and GI rays, voxels, AO) sees both sides, as a closed
// interior modelled with single-sided walls needs (its walls keep the sun out), and shades its
// back as the back side (the normal turned towards the viewer or the ray). The front is where
// the triangle's object-space normal (p1 - p0) x (p2 - p0) points, carried to the world by the
// instance's normal matrix: a mirroring transform (negative determinant) keeps the front where
// glTF says it is (its winding is then clockwise).
TL_CONST uint kMaterialDoubleSided = 1u;
TL_FN bool tlMaterialCulledFromBehind(uint flags) { return (flags & kMaterialDoubleSided) == 0u; }
// KHR_materials_unlit: the surface shows its base colour (factor x texture x COLOR_0) whatever
// the light, and reflects nothing. Shaded as emission of that radiance over a black surface
// with no specular layer, so every path and the reference show it the same way (and, like any
// emitter, it lights what it faces in the paths that gather emission).
TL_CONST uint kMaterialUnlit = 2u;

// KHR_materials_ior and KHR_materials_specular: the dielectric's F0 (rgb) and F90 (w) from the
// ior, specularColor (factor x texture) and specular (factor x texture alpha):
//   F0 = min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular,   F90 = specular.
// Their defaults (1.5, 1, 1) give glTF's core 0.04 and 1 (shared/shading.h).
TL_FN vec4 tlDielectricFresnel(float ior, vec3 specularColor, float specular) {
  float r = (ior - 1.0f) / (ior + 1.0f);
  return vec4(min(vec3(r * r) * specularColor, vec3(1.0f)) * specular, specular);
}

// Where a slot samples its texture for a point with UV sets uv0 and uv1.
TL_FN vec2 tlSlotUv(GpuTextureSlot s, vec2 uv0, vec2 uv1) {
  vec2 uv = s.texCoord == 1u ? uv1 : uv0;
  return vec2(s.linear.x * uv.x + s.linear.z * uv.y, s.linear.y * uv.x + s.linear.w * uv.y) + s.offset;
}

// One instance, std430. The transform is camera-relative: the translation has the camera
// position subtracted in double precision on the CPU, so float on the GPU stays exact near
// the viewer however far the scene is from the origin.
struct GpuInstance {
  mat4 modelRelative;       // object -> camera-relative world
  mat4 prevModelRelative;   // previous frame, relative to this frame's camera (motion vectors)
  mat4 normalMatrix;        // inverse transpose of the upper 3x3, in a mat4 for alignment
  uint material;
  uint instanceId;          // written to the G-buffer's instance id (0 is "nothing")
  uint vertexOffset;        // where its mesh's vertices start in the vertex buffer (for shaders that fetch them)
  uint previousPositionOffset;  // a deforming mesh's: where its last frame's positions start in
                                // scene.vertices.previous; kNoPreviousPositions for a rigid one
};
// A rigid mesh's vertices were where they are: its motion is its instance's.
TL_CONST uint kNoPreviousPositions = 0xFFFFFFFFu;

// glTF's alpha modes. BLEND is stochastic transparency: a surface of alpha a is there for a
// fraction a of the samples a stage takes (pixels, shadow-map texels, voxels, rays, frames) and
// absent for the rest, so it stops a of the light and shows a of its own colour once those
// samples are averaged (by a filter, TAA, temporal accumulation or the reference's mean).
TL_CONST uint kAlphaOpaque = 0u;
TL_CONST uint kAlphaMask = 1u;
TL_CONST uint kAlphaBlend = 2u;

// True where a surface is cut away at this alpha: MASK below its cutoff, BLEND where alpha
// does not exceed xi, the stage's uniform number in [0, 1) for this sample. One predicate for
// every stage that sees a surface (G-buffer, shadow maps, voxelizer, any-hit shaders).
TL_FN bool tlMaterialCutout(uint alphaMode, float alphaCutoff, float alpha, float xi) {
  if (alphaMode == kAlphaMask) return alpha < alphaCutoff;
  if (alphaMode == kAlphaBlend) return alpha <= xi;
  return false;
}

// KHR_materials_transmission in the G-buffer paths (rt and legacy), which have one surface per
// pixel: a transmitting surface is stochastic coverage, as alpha BLEND is. It is there for the
// share of the samples (pixels, shadow-map texels, voxels, rays) it does not let through at normal
// incidence, 1 - t (1 - metallic) lum(baseColor) (1 - lum(F0_d)), and absent for the rest, where
// what lies behind it is seen and lit. The light it passes is then right in luminance at normal
// incidence; its tint, its Fresnel's rise at grazing angles and the part of its reflection that
// the absent samples lose are not (the reference renders all three: shared/shading.h). Computed
// from the authored material in every override mode.
TL_FN float tlTransmissionCoverage(float transmission, float metallic, vec3 baseColor, vec3 dielectricF0) {
  float through = clamp(transmission, 0.0f, 1.0f) * (1.0f - clamp(metallic, 0.0f, 1.0f)) *
                  clamp(tlLuminance(baseColor), 0.0f, 1.0f) * (1.0f - clamp(tlLuminance(dielectricF0), 0.0f, 1.0f));
  return 1.0f - through;
}

// tlMaterialCutout with that coverage: cut where alpha cuts, or where the surface's presence
// (alpha x coverage for BLEND, coverage otherwise) does not exceed xi.
TL_FN bool tlMaterialCutoutTransmitting(uint alphaMode, float alphaCutoff, float alpha, float coverage, float xi) {
  if (alphaMode == kAlphaMask && alpha < alphaCutoff) return true;
  if (alphaMode == kAlphaBlend) return alpha * coverage <= xi;
  return coverage < 1.0f && coverage <= xi;
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::GpuTextureSlot) == 32);
static_assert(sizeof(tl::shared::GpuMaterial) == 368);
static_assert(sizeof(tl::shared::GpuInstance) == 208);
#endif
#endif
