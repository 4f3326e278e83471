#version 460
// Mip 0 of the hierarchical depth (shared/legacy_reflections.h): the G-buffer's reversed-Z
// depth, as a storage image the next mips reduce.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/legacy_reflections.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLegacyBindingHizOut, r32f) uniform writeonly image2D hizOut;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  imageStore(hizOut, p, vec4(texelFetch(gDepth, p, 0).r));
}
