#version 460
// The radiance cache's sums (shared/rt_cache.h): one invocation per cell and per sample.
// A cell's invocation clears the sum the next frame adds into (the other parity) and drops a
// cell without samples for RtCachePush::maxAge frames; a sample's invocation finds or claims
// its cell and its coarse cell (linear probing, compare-and-swap on the key) and adds itself to
// both in fixed point.
// On a restart every cell is emptied and no sample is taken.
#extension GL_GOOGLE_include_directive : require
#include "shared/rt.h"
#include "shared/rt_cache.h"

layout(local_size_x = 64) in;
layout(set = 0, binding = kRtBindingCacheSamples, std430) readonly buffer Samples { RtCacheSample samples[]; };
layout(set = 0, binding = kRtBindingCacheAccum, std430) buffer Accum { RtCacheAccum accum[]; };
layout(push_constant) uniform Push { RtCachePush push; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint current = push.frame & 1u, next = current ^ 1u;
  if (i <= push.entryMask) {
    if (push.restart != 0u) {
      accum[i].key = 0u;
      accum[i].stamp = 0u;
      for (uint k = 0u; k < 8u; ++k) accum[i].sum[k] = 0u;
    } else {
      for (uint k = 0u; k < 4u; ++k) accum[i].sum[4u * next + k] = 0u;
      if (accum[i].key != 0u && push.frame - accum[i].stamp > push.maxAge) accum[i].key = 0u;
    }
  }
  if (push.restart != 0u || i >= push.sampleCount) return;
  RtCacheSample s = samples[i];
  if (s.cell.y == 0u) return;
  // The sample goes to its cell and to its coarse cell (shared/rt_cache.h).
  for (uint level = 0u; level < 2u; ++level) {
    uvec2 cell = level == 0u ? s.cell.xy : s.cell.zw;
    uvec3 h = tlPcg3d(uvec3(i, push.frame, 0x2545F491u + level));
    for (uint k = 0u; k < kRtCacheProbes; ++k) {
      uint slot = (cell.x + k) & push.entryMask;
      uint owner = atomicCompSwap(accum[slot].key, 0u, cell.y);
      if (owner != 0u && owner != cell.y) continue;
      accum[slot].stamp = push.frame;
      uint at = 4u * current;
      if (atomicAdd(accum[slot].sum[at + 3u], 1u) < kRtCacheSampleCap) {
        atomicAdd(accum[slot].sum[at], tlRtCacheToFixed(s.radiance.r, push.bound, tlUintToUnitFloat(h.x)));
        atomicAdd(accum[slot].sum[at + 1u], tlRtCacheToFixed(s.radiance.g, push.bound, tlUintToUnitFloat(h.y)));
        atomicAdd(accum[slot].sum[at + 2u], tlRtCacheToFixed(s.radiance.b, push.bound, tlUintToUnitFloat(h.z)));
      }
      break;
    }
  }
}
