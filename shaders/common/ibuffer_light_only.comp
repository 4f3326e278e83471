#version 460
// ibuffer.lightOnly: the I-buffer resolved against white (shared/redeferred.h
// tlIbufferLightOnly): the light the artist placed, without the materials. Sky pixels show
// the sky. Runs only in frames that read it (the editor's "Light only" view, captures).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/redeferred.h"
#include "shared/shading.h"
#include "shared/environment.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kIbufferNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kIbufferMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kIbufferDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kIbufferSumDg) uniform sampler2D iDg;
layout(set = 0, binding = kIbufferSumSg1) uniform sampler2D iSg1;
layout(set = 0, binding = kIbufferSumSg2) uniform sampler2D iSg2;
layout(set = 0, binding = kIbufferSumMs) uniform sampler2D iMs;
layout(set = 0, binding = kIbufferLightOnlyOut, rgba32f) uniform writeonly image2D outLight;

#include "common/camera.glsl"
#include "common/environment.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  if (depth <= 0.0) {  // reversed Z: nothing drawn, the sky is visible
    imageStore(outLight, p, vec4(environmentRadiance(cameraRay(uv * 2.0 - 1.0).direction), 1.0));
    return;
  }
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 v = towardsViewer(cameraRelativePosition(uv, depth));
  uint materials = tlFrameMaterials(frame.flags);
  IbufferSums sums;
  sums.dg = texelFetch(iDg, p, 0).rgb;
  sums.sg1 = texelFetch(iSg1, p, 0).rgb;
  sums.sg2 = texelFetch(iSg2, p, 0).rgb;
  sums.ms = texelFetch(iMs, p, 0).rgb;
  float roughness = tlMaterialRoughness(texelFetch(gMaterial, p, 0).x, materials);
  imageStore(outLight, p, vec4(tlIbufferLightOnly(roughness, materials, dot(n, v), sums), 1.0));
}
