#version 460
// The pass builder's optional input (shared/pass_builder_test.h): reads the source only when
// the pass says it is bound; otherwise the binding is left unwritten (partially bound).
#extension GL_GOOGLE_include_directive : require
#include "shared/pass_builder_test.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kOptionalInputSource) uniform sampler2D source;
layout(set = 0, binding = kOptionalInputResult, r32f) uniform writeonly image2D result;
layout(push_constant) uniform Push { OptionalInputPush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(result)))) return;
  float v = push.present != 0u ? texelFetch(source, p, 0).r : push.fallback;
  imageStore(result, p, vec4(v));
}
