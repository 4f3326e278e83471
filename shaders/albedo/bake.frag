#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/albedo.h"
#include "shared/rt.h"
#include "common/material.glsl"

// The hit albedo a ray would read at this texel (Metro's albedo (1 - F0) + F0); alpha marks
// coverage. Cut-out texels are not covered; a translucent (BLEND) surface covers every texel
// where its alpha is above 0 (its albedo is its colour where it is there at all).
layout(push_constant) uniform Draw { AlbedoBakeDraw draw; };

layout(location = 0) in vec2 inUv;
layout(location = 1) in vec2 inUv1;
layout(location = 2) in vec4 inColor;
layout(location = 0) out vec4 outAlbedo;

void main() {
  GpuMaterial m = materials[draw.material];
  vec4 base = materialBaseColor(m, inUv, inUv1, inColor);
  if (materialCutout(m, base.a, 0.0)) discard;
  float metallic = clamp(materialRoughnessMetallic(m, inUv, inUv1).y, 0.0, 1.0);
  outAlbedo = vec4(tlRtHitAlbedoFromMaterial(clamp(base.rgb, 0.0, 1.0), metallic), 1.0);
}
