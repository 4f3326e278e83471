#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/display.h"
#include "shared/color.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kDisplaySource) uniform sampler2D source;
layout(set = 0, binding = kDisplayInstanceId) uniform usampler2D instanceId;
layout(set = 0, binding = kDisplayOutput, rgba8) uniform writeonly image2D display;
layout(push_constant) uniform Push { DisplayPush push; };

#include "common/display_outline.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(display);
  if (any(greaterThanEqual(p, size))) return;
  // The source may differ in size from the display (a shadow map): sample by UV.
  vec2 uv = (vec2(p) + 0.5) / vec2(size);
  vec4 v = textureLod(source, uv, 0.0);
  vec3 c;
  if (push.mode == kDisplayModeFinal) {
    c = v.rgb;
  } else {
    if (push.channels == 1u) v = vec4(v.r, v.r, v.r, 1.0);
    if (push.channels == 2u) v = vec4(v.r, v.g, 0.0, 1.0);
    c = tlLinearToSrgb(abs(v.rgb) * push.scale);
  }
  imageStore(display, p, vec4(outline(p, size, c), 1.0));
}
