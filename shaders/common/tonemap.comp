#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/color.h"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kTonemapInput) uniform sampler2D hdr;
layout(set = 0, binding = kTonemapOutput, rgba8) uniform writeonly image2D ldr;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  vec3 radiance = max(texelFetch(hdr, p, 0).rgb, vec3(0.0));
  // A debug view's values as they are; radiance through exposure and the tonemap curve.
  vec3 display = (frame.flags & kFrameFlagShowValues) != 0u ? min(radiance, vec3(1.0)) : tlTonemapAces(radiance * frame.exposure);
  imageStore(ldr, p, vec4(tlLinearToSrgb(display), 1.0));
}
