// One workgroup's RefNoiseTotals (shared/reference.h) summed in shared memory: each invocation
// hands in its own, invocation 0 gets the group's. Sums add, counts add, the fewest and most
// samples take the minimum and maximum. The includer sets local_size to kNoiseGroupSize
// invocations.
const uint kNoiseGroupSize = 256u;
shared vec4 gSums[kNoiseGroupSize];
shared uvec4 gCounts[kNoiseGroupSize];

RefNoiseTotals noiseNone() {
  RefNoiseTotals t;
  t.sums = vec4(0.0);
  t.counts = uvec4(0u, 0u, 0xFFFFFFFFu, 0u);
  return t;
}

RefNoiseTotals noiseGroupSum(RefNoiseTotals mine) {
  uint i = gl_LocalInvocationIndex;
  gSums[i] = mine.sums;
  gCounts[i] = mine.counts;
  barrier();
  for (uint stride = kNoiseGroupSize / 2u; stride > 0u; stride /= 2u) {
    if (i < stride) {
      uvec4 a = gCounts[i], b = gCounts[i + stride];
      gSums[i] += gSums[i + stride];
      gCounts[i] = uvec4(a.x + b.x, a.y + b.y, min(a.z, b.z), max(a.w, b.w));
    }
    barrier();
  }
  RefNoiseTotals t;
  t.sums = gSums[0];
  t.counts = gCounts[0];
  return t;
}
