#version 460
// Alpha test for the sun shadow map: the same cut-out as the G-buffer (material.glsl).
#extension GL_GOOGLE_include_directive : require
#include "shared/scene.h"
#include "common/material.glsl"

layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inInstance;
layout(location = 2) in vec2 inUv1;
layout(location = 3) in float inAlpha;

void main() {
  GpuMaterial m = materials[instances[inInstance].material];
  if (materialCutout(m, materialBaseColor(m, inUv, inUv1, vec4(1.0, 1.0, 1.0, inAlpha)).a)) discard;
}
