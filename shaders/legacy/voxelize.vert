#version 460
// Voxelization: each triangle is rasterised orthographically along one axis into an R x R
// viewport covering one clipmap level; the fragment shader writes the voxel it lands in.
// Three passes (x, y, z) per level catch surfaces at any orientation. A partial update draws
// only the instances near its region, with a scissor around it (legacy_path.cpp).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/legacy.h"
#include "shared/scene.h"

layout(location = kAttrPosition) in vec3 inPosition;
layout(location = kAttrNormal) in vec3 inNormal;
layout(location = kAttrUv) in vec2 inUv;
layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { LegacyVoxelPush push; };

layout(location = 0) out vec3 outPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) flat out uint outInstance;

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  vec3 world = vec3(inst.modelRelative * vec4(inPosition, 1.0));
  uint axis = push.axis % 3u, level = push.axis / 3u;
  vec4 box = push.clipmap.levelMin[level];
  vec3 t = (world - box.xyz) / (box.w * float(push.clipmap.resolution));  // [0,1] inside the level
  vec3 swizzled = axis == 0u ? t.yzx : (axis == 1u ? t.zxy : t.xyz);
  gl_Position = vec4(swizzled.xy * 2.0 - 1.0, clamp(swizzled.z, 0.0, 1.0), 1.0);
  outPosition = world;
  outNormal = mat3(inst.normalMatrix) * inNormal;
  outUv = inUv;
  outInstance = uint(gl_InstanceIndex);
}
