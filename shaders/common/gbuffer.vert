#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/scene.h"

layout(location = kAttrPosition) in vec3 inPosition;
layout(location = kAttrNormal) in vec3 inNormal;
layout(location = kAttrTangent) in vec4 inTangent;
layout(location = kAttrUv) in vec2 inUv;
layout(location = kAttrUv1) in vec2 inUv1;
layout(location = kAttrColor) in vec4 inColor;

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = kGbufferPreviousPositions, std430) readonly buffer PreviousPositions { vec4 previousPositions[]; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec4 outTangent;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outClip;
layout(location = 4) out vec4 outPrevClip;
layout(location = 5) flat out uint outInstance;
layout(location = 6) out vec2 outUv1;
layout(location = 7) out vec4 outColor;

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  vec4 relative = inst.modelRelative * vec4(inPosition, 1.0);
  vec4 clip = frame.viewProj * relative;
  // Motion vectors join unjittered positions: TAA's sub-pixel shift (in viewProj, not in
  // prevViewProj) is taken out again, so a still camera has zero motion.
  outClip = clip - vec4(frame.jitter.xy * clip.w, 0.0, 0.0);
  // A deforming mesh's vertex was elsewhere last frame: its motion is the instance's and its own.
  vec3 previousPosition = inPosition;
  if (inst.previousPositionOffset != kNoPreviousPositions)
    previousPosition = previousPositions[inst.previousPositionOffset + uint(gl_VertexIndex) - inst.vertexOffset].xyz;
  outPrevClip = frame.prevViewProj * (inst.prevModelRelative * vec4(previousPosition, 1.0));
  outNormal = mat3(inst.normalMatrix) * inNormal;
  outTangent = vec4(mat3(inst.modelRelative) * inTangent.xyz, inTangent.w);
  outUv = inUv;
  outUv1 = inUv1;
  outColor = inColor;
  outInstance = uint(gl_InstanceIndex);
  gl_Position = clip;
}
