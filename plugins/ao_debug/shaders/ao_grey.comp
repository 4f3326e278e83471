#version 460
// The AO as the whole image: grey = visibility (1 white, unoccluded), black on the sky, so
// the radiance the composite passes through is the AO itself (EXR captures hold its values).
#extension GL_GOOGLE_include_directive : require
#include "ao_debug.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kAoDebugSource) uniform sampler2D ao;
layout(set = 0, binding = kAoDebugDepth) uniform sampler2D depth;
layout(set = 0, binding = kAoDebugOutput, rgba32f) uniform writeonly image2D outGrey;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(outGrey);
  if (any(greaterThanEqual(p, size))) return;
  float visibility = 0.0;
  if (texelFetch(depth, p, 0).r > 0.0) visibility = textureLod(ao, (vec2(p) + 0.5) / vec2(size), 0.0).r;
  imageStore(outGrey, p, vec4(vec3(visibility), 1.0));
}
