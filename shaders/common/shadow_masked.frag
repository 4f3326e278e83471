#version 460
// Alpha test for the shadow maps (the sun's and the lights'): the same cut-out as the G-buffer
// (material.glsl). A translucent (BLEND) caster covers alpha of every 4x4 block of texels with
// a still ordered dither: the shadow filter's footprint averages it to a transmission of 1 - alpha.
#extension GL_GOOGLE_include_directive : require
#include "shared/sampling.h"
#include "shared/scene.h"
#include "common/material.glsl"

layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inInstance;
layout(location = 2) in vec2 inUv1;
layout(location = 3) in float inAlpha;

void main() {
  GpuMaterial m = materials[instances[inInstance].material];
  vec4 base = materialBaseColor(m, inUv, inUv1, vec4(1.0, 1.0, 1.0, inAlpha));
  float coverage = materialCoverage(m, inUv, inUv1, base.rgb);
  if (materialCutoutTransmitting(m, base.a, coverage, tlOrderedDither4(uint(gl_FragCoord.x), uint(gl_FragCoord.y)))) discard;
}
