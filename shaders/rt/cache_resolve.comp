#version 460
// The radiance cache as hits read it (shared/rt_cache.h): each cell's samples of this frame
// blended into its radiance, a history of at most RtCachePush::maxSamples samples fading over
// kRtCacheHistoryFrames frames. A slot
// that changed hands starts over; an empty one (or every one on a restart) is cleared.
#extension GL_GOOGLE_include_directive : require
#include "shared/rt.h"
#include "shared/rt_cache.h"

layout(local_size_x = 64) in;
layout(set = 0, binding = kRtBindingCacheAccum, std430) readonly buffer Accum { RtCacheAccum accum[]; };
layout(set = 0, binding = kRtBindingCacheEntries, std430) buffer Entries { RtCacheEntry entries[]; };
layout(push_constant) uniform Push { RtCachePush push; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i > push.entryMask) return;
  RtCacheEntry e = entries[i];
  uint key = push.restart != 0u ? 0u : accum[i].key;
  if (key == 0u) {
    entries[i].radiance = vec4(0.0);
    entries[i].key = 0u;
    return;
  }
  if (e.key != key) e.radiance = vec4(0.0);
  uint at = 4u * (push.frame & 1u);
  float n = float(min(accum[i].sum[at + 3u], kRtCacheSampleCap));
  vec3 mean = vec3(0.0);
  if (n > 0.0)
    mean = vec3(tlRtCacheFromFixed(accum[i].sum[at], push.bound), tlRtCacheFromFixed(accum[i].sum[at + 1u], push.bound),
                tlRtCacheFromFixed(accum[i].sum[at + 2u], push.bound)) / n;
  e.radiance = tlRtCacheBlend(e.radiance, mean, n, push.maxSamples, push.historyDecay);
  // A cell whose samples all faded out holds nothing: hits read it as empty.
  if (n <= 0.0 && e.radiance.w < 1e-3) e.radiance.w = 0.0;
  entries[i].radiance = e.radiance;
  entries[i].key = key;
}
