#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/scene.h"

layout(location = kAttrPosition) in vec3 inPosition;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  gl_Position = frame.sunViewProj * (inst.modelRelative * vec4(inPosition, 1.0));
}
