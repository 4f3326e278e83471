#version 460
// shadow.lights: depth of every caster seen from one view of a point or spot light
// (shared/lights.h GpuShadowView), drawn into that view's tile of the atlas.
#extension GL_GOOGLE_include_directive : require
#include "shared/lights.h"
#include "shared/scene.h"

layout(location = kAttrPosition) in vec3 inPosition;
layout(set = 0, binding = kBindingLightShadowViews, std430) readonly buffer Views { GpuShadowView views[]; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { LightShadowPush push; };

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  gl_Position = views[push.view].viewProj * (inst.modelRelative * vec4(inPosition, 1.0));
}
