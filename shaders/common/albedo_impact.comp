#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/albedo.h"

// What the albedo edits changed: |this frame - the frame before them|, per channel; alpha
// the signed luminance change.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kAlbedoViewBindingCurrent) uniform sampler2D current;
layout(binding = kAlbedoViewBindingBaseline) uniform sampler2D baseline;
layout(binding = kAlbedoViewBindingImpact, rgba16f) uniform writeonly image2D impactOut;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(impactOut)))) return;
  vec3 d = texelFetch(current, p, 0).rgb - texelFetch(baseline, p, 0).rgb;
  imageStore(impactOut, p, vec4(abs(d), dot(d, vec3(0.2126, 0.7152, 0.0722))));
}
