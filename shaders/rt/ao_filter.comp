#version 460
// RTAO spatial filter: 3x3 taps two pixels apart (a 5x5 footprint for nine fetches),
// weighted by view-depth similarity so occlusion does not bleed across edges.
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtAoFilterAccumulated) uniform sampler2D accumulated;  // .z: AO
layout(set = 0, binding = kRtAoFilterViewDepth) uniform sampler2D viewDepth;
layout(set = 0, binding = kRtAoFilterOut, r16f) uniform writeonly image2D aoOut;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float w0 = texelFetch(viewDepth, p, 0).r;
  if (w0 <= 0.0) {
    imageStore(aoOut, p, vec4(1.0));
    return;
  }
  float sum = 0.0, weight = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(p + 2 * ivec2(x, y), ivec2(0), size - 1);
      float w = texelFetch(viewDepth, q, 0).r;
      float d = abs(w - w0) / (w0 * kRtAoFilterDepth);
      float k = (w > 0.0 ? 1.0 : 0.0) / (1.0 + d * d);
      sum += k * texelFetch(accumulated, q, 0).z;
      weight += k;
    }
  imageStore(aoOut, p, vec4(weight > 0.0 ? sum / weight : 1.0));
}
