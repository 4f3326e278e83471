#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/albedo.h"
#include "shared/scene.h"

// One combination seen from one direction; the pass makes its tile of the atlas the viewport.
layout(push_constant) uniform Draw { AlbedoBakeDraw draw; };

layout(location = kAttrPosition) in vec3 inPosition;
layout(location = kAttrUv) in vec2 inUv;
layout(location = kAttrUv1) in vec2 inUv1;
layout(location = kAttrColor) in vec4 inColor;
layout(location = 0) out vec2 outUv;
layout(location = 1) out vec2 outUv1;
layout(location = 2) out vec4 outColor;

void main() {
  outUv = inUv;
  outUv1 = inUv1;
  outColor = inColor;
  gl_Position = draw.objectToClip * vec4(inPosition, 1.0);
}
