#version 460
// The reference's noise, second step: one workgroup sums every tile's RefNoiseTotals into
// the image's (reference.noise), which the session reads back each frame and the next frame's
// trace allocates its samples by (its mean sigma).
#extension GL_GOOGLE_include_directive : require
#include "shared/reference.h"

layout(local_size_x = 256) in;
layout(set = 0, binding = kRefNoiseBindingTiles, std430) readonly buffer Tiles { RefNoiseTotals tiles[]; };
layout(set = 0, binding = kRefNoiseBindingTotals, std430) writeonly buffer Totals { RefNoiseTotals totals; };
layout(push_constant) uniform Push { RefNoisePush push; };

#include "reference/noise_reduce.glsl"

void main() {
  RefNoiseTotals mine = noiseNone();
  for (uint i = gl_LocalInvocationIndex; i < push.tiles; i += kNoiseGroupSize) {
    RefNoiseTotals t = tiles[i];
    mine.sums += t.sums;
    mine.counts = uvec4(mine.counts.x + t.counts.x, mine.counts.y + t.counts.y, min(mine.counts.z, t.counts.z),
                        max(mine.counts.w, t.counts.w));
  }
  RefNoiseTotals t = noiseGroupSum(mine);
  if (gl_LocalInvocationIndex == 0u) totals = t;
}
