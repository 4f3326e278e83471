#version 460
// light_shadow.vert for cut-out (alpha MASK) casters: plus the UVs, the vertex alpha and the instance that
// shadow_masked.frag's alpha test needs.
#extension GL_GOOGLE_include_directive : require
#include "shared/lights.h"
#include "shared/scene.h"

layout(location = kAttrPosition) in vec3 inPosition;
layout(location = kAttrUv) in vec2 inUv;
layout(location = kAttrUv1) in vec2 inUv1;
layout(location = kAttrColor) in vec4 inColor;
layout(set = 0, binding = kBindingLightShadowViews, std430) readonly buffer Views { GpuShadowView views[]; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { LightShadowPush push; };

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;
layout(location = 2) out vec2 outUv1;
layout(location = 3) out float outAlpha;

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  gl_Position = views[push.view].viewProj * (inst.modelRelative * vec4(inPosition, 1.0));
  outUv = inUv;
  outUv1 = inUv1;
  outAlpha = inColor.a;
  outInstance = gl_InstanceIndex;
}
