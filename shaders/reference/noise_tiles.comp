#version 460
// The reference's noise, first step: each 16 x 16 tile of the image sums the variance of its
// pixels' estimates (reference.stderr squared), the estimates (reference.radiance), the
// samples, over the three channels, and the sigma adaptive sampling allocates the next frame's
// samples by (reference.allocation z), into one RefNoiseTotals.
#extension GL_GOOGLE_include_directive : require
#include "shared/reference.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = kRefNoiseBindingRadiance, rgba32f) uniform readonly image2D radiance;
layout(set = 0, binding = kRefNoiseBindingStdErr, rgba32f) uniform readonly image2D stdErr;
layout(set = 0, binding = kRefNoiseBindingAllocation, rgba32f) uniform readonly image2D allocation;
layout(set = 0, binding = kRefNoiseBindingTiles, std430) writeonly buffer Tiles { RefNoiseTotals tiles[]; };
layout(push_constant) uniform Push { RefNoisePush push; };

#include "reference/noise_reduce.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  RefNoiseTotals mine = noiseNone();
  if (p.x < int(push.width) && p.y < int(push.height)) {
    vec4 e = imageLoad(stdErr, p);
    vec3 r = imageLoad(radiance, p).rgb;
    mine.sums = vec4(dot(e.rgb, e.rgb), r.r + r.g + r.b, e.a, imageLoad(allocation, p).z);
    uint n = uint(e.a);
    mine.counts = uvec4(1u, n < 2u ? 1u : 0u, n, n);
  }
  RefNoiseTotals t = noiseGroupSum(mine);
  if (gl_LocalInvocationIndex == 0u) tiles[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = t;
}
