#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/scene.h"
#include "shared/gbuffer.h"
#include "shared/packing.h"
#include "shared/sampling.h"
#include "common/material.glsl"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inTangent;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inClip;
layout(location = 4) in vec4 inPrevClip;
layout(location = 5) flat in uint inInstance;
layout(location = 6) in vec2 inUv1;
layout(location = 7) in vec4 inColor;

layout(location = kGbufferBaseColor) out vec4 outBaseColor;
layout(location = kGbufferNormal) out vec2 outNormal;
layout(location = kGbufferMaterial) out vec4 outMaterial;
layout(location = kGbufferEmissive) out vec4 outEmissive;
layout(location = kGbufferMotion) out vec2 outMotion;
layout(location = kGbufferInstanceId) out uint outInstanceId;

void main() {
  GpuInstance inst = instances[inInstance];
  GpuMaterial m = materials[inst.material];

  // The material override mode (shared/material_mode.h) decides what reaches the G-buffer; a
  // cut-out or a translucent surface keeps its texture's alpha in every mode.
  uint materials = tlFrameMaterials(frame.flags);
  vec4 base = materialBaseColor(m, inUv, inUv1, inColor);
  bool framesAveraged = (frame.flags & kFrameFlagFramesAveraged) != 0u;
  float xi = tlAlphaDither(uint(gl_FragCoord.x), uint(gl_FragCoord.y), frame.frameIndex, framesAveraged);
  if (materialCutoutTransmitting(m, base.a, materialCoverage(m, inUv, inUv1, base.rgb), xi)) discard;

  // The glTF front (shared/scene.h): the rasterizer's facing of the world-space winding, turned
  // over where the instance mirrors (the winding is then clockwise). Single-sided surfaces seen
  // from behind are culled; double-sided ones shade their back side (the normal faces the viewer).
  bool front = gl_FrontFacing == (determinant(mat3(inst.modelRelative)) > 0.0);
  if (!front && tlMaterialCulledFromBehind(m.flags)) discard;
  vec3 n = normalize(inNormal);
  if (!front) n = -n;
  if (m.normalTexture.texture != kNoTexture && tlMaterialNormalMaps(materials))
    n = normalMapped(n, inTangent, sampleSlot(m.normalTexture, inUv, inUv1).xyz, m.normalScale);

  vec2 rm = materialRoughnessMetallic(m, inUv, inUv1);
  float roughness = tlMaterialRoughness(rm.x, materials);
  float metallic = tlMaterialMetallic(rm.y, materials);
  vec3 emissive = materialEmission(m, inUv, inUv1);
  vec4 fresnel = materialDielectricFresnel(m, inUv, inUv1);
  vec3 baseColor = clamp(tlMaterialBaseColor(base.rgb, materials), 0.0, 1.0);
  // Unlit (shared/scene.h): the base colour as emission over a black surface with no specular.
  if ((m.flags & kMaterialUnlit) != 0u) {
    emissive += baseColor;
    baseColor = vec3(0.0);
    fresnel = vec4(0.0);
  }
  float occlusion = tlMaterialOcclusion(materialOcclusion(m, inUv, inUv1), materials);

  vec2 ndc = inClip.xy / inClip.w;
  vec2 prevNdc = inPrevClip.xy / inPrevClip.w;

  outBaseColor = vec4(baseColor, clamp(fresnel.w, 0.0, 1.0));
  outNormal = tlOctEncode(n);
  outMaterial = vec4(clamp(roughness, 0.0, 1.0), clamp(metallic, 0.0, 1.0), tlGbufferEncodeF0(fresnel.rgb), clamp(occlusion, 0.0, 1.0));
  outEmissive = vec4(emissive, 1.0);
  outMotion = (ndc - prevNdc) * 0.5;
  outInstanceId = inst.instanceId;
}
