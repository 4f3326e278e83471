#version 460
// ibuffer.light: the I-buffer (shared/redeferred.h) of every light the deferred composite
// shades through the BRDF's light loop: the sun through its shadow map, the light table's
// share (lights.L*, when the scene has lights), and the path's diffuse irradiance (the sky or
// its GI, times AO). It reads the G-buffer's geometry (depth, normal, roughness), never its
// colour: what it writes is the light arriving at each pixel, without the material.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/packing.h"
#include "shared/redeferred.h"
#include "shared/shading.h"
#include "shared/sh.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kIbufferNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kIbufferMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kIbufferDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kIbufferShadow) uniform sampler2DShadow sunShadow;
layout(set = 0, binding = kIbufferOutDg, rgba32f) uniform writeonly image2D outDg;
layout(set = 0, binding = kIbufferOutSg1, rgba32f) uniform writeonly image2D outSg1;
layout(set = 0, binding = kIbufferOutSg2, rgba32f) uniform writeonly image2D outSg2;
layout(set = 0, binding = kIbufferOutMs, rgba32f) uniform writeonly image2D outMs;
layout(set = 0, binding = kIbufferLightsDg) uniform sampler2D lightsDg;
layout(set = 0, binding = kIbufferLightsSg1) uniform sampler2D lightsSg1;
layout(set = 0, binding = kIbufferLightsSg2) uniform sampler2D lightsSg2;
layout(set = 0, binding = kIbufferLightsMs) uniform sampler2D lightsMs;
layout(set = 0, binding = kIbufferRefineMaskSampled) uniform sampler2D refineMask;
layout(set = 0, binding = kIbufferFilledDg) uniform sampler2D filledDg;  // the refining run: ibuffer.filled.*
layout(set = 0, binding = kIbufferFilledSg1) uniform sampler2D filledSg1;
layout(set = 0, binding = kIbufferFilledSg2) uniform sampler2D filledSg2;
layout(set = 0, binding = kIbufferFilledMs) uniform sampler2D filledMs;
layout(set = 0, binding = kIbufferSunVisibility) uniform sampler2D sunVisibilityHybrid;
layout(push_constant) uniform Push { CompositePush push; };

#include "common/camera.glsl"
#include "common/ibuffer_stage.glsl"
#include "common/path_indirect.glsl"

#define TL_SUN_SHADOW_PCSS
#define TL_SUN_VISIBILITY_HYBRID
layout(set = 0, binding = kIbufferShadowDepth) uniform sampler2D sunShadowDepth;
#include "common/sun_shadow.glsl"

void store(ivec2 p, IbufferSums sums) {
  imageStore(outDg, p, vec4(sums.dg, 1.0));
  imageStore(outSg1, p, vec4(sums.sg1, 1.0));
  imageStore(outSg2, p, vec4(sums.sg2, 1.0));
  imageStore(outMs, p, vec4(sums.ms, 1.0));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (push.ibufferStage == kIbufferStageRefine) {
    // The whole I-buffer: the filled (and pattern) pixels as ibuffer.upsample left them, the
    // marked ones shaded below.
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    if (texelFetch(refineMask, p, 0).r != kIbufferRefined) {
      imageStore(outDg, p, texelFetch(filledDg, p, 0));
      imageStore(outSg1, p, texelFetch(filledSg1, p, 0));
      imageStore(outSg2, p, texelFetch(filledSg2, p, 0));
      imageStore(outMs, p, texelFetch(filledMs, p, 0));
      return;
    }
  } else {
    p = ibufferStagePixel(push.ibufferStage, push.ibufferPattern);
    if (p.x < 0) return;
  }
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: no surface (the material pass shows the sky's radiance)
    store(p, tlIbufferZero());
    return;
  }
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  vec3 position = cameraRelativePosition(uv, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 v = towardsViewer(position);
  uint materials = tlFrameMaterials(frame.flags);
  vec4 material = texelFetch(gMaterial, p, 0);
  SurfaceParams g = tlIbufferSurface(tlMaterialRoughness(material.x, materials), materials);

  IbufferSums sums = tlIbufferZero();
  vec3 l = frame.sunToLight.xyz;
  float nl = dot(n, l);
  if (nl > 0.0) sums = tlIbufferAddLight(sums, g, n, v, l, frame.sunIrradiance.rgb * (nl * sunVisibilityShading(position, n, p)));
  if ((push.flags & kCompositeHasLights) != 0u) {
    sums.dg += texelFetch(lightsDg, p, 0).rgb;
    sums.sg1 += texelFetch(lightsSg1, p, 0).rgb;
    sums.sg2 += texelFetch(lightsSg2, p, 0).rgb;
    sums.ms += texelFetch(lightsMs, p, 0).rgb;
  }
  // The diffuse irradiance with AO as a black surface sees it: the occluders' light that
  // multi-bounce AO puts back depends on the surface's albedo, so the material pass adds it.
  // Times the material's occlusion (gbuffer.material.a), as the composite applies it.
  float ao = pathAmbientOcclusion(p);
  sums = tlIbufferAddIrradiance(sums, g, material.w * pathDiffuseIrradiance(p, n, position, ao, vec3(0.0), tlSkyIrradiance(frame, n)));
  store(p, sums);
}
