// The RT path's world-space radiance cache (after NVIDIA's spatially hashed radiance cache,
// SHaRC): the multi-bounce light at GI hits that are not on screen. Shared by C++ (the path,
// the tests) and GLSL (rt/cache_*.{rgen,comp}, rt/hit_lighting.glsl).
//
// What a cell holds: C(x), the cosine-weighted mean of the radiance arriving at the surfaces
// in it from every direction, leaving out what is sampled explicitly at a hit (the sun and,
// with emitter sampling, the emitters). A hit's outgoing light is then its own direct light
// plus albedo * C: the cache replaces the one sky ray a hit lit afresh traces, and carries
// every bounce beyond it (the sky seen after any number of bounces, the sun's light off walls
// that are off screen).
//
// Cells: a hash of the world position quantized at a size that grows with the distance from
// the camera (level L: RtPush::cacheCellSize * 2^L, the smallest at least `cellAngle` times the
// distance), the level and the normal's dominant axis and sign (the two sides of a wall, a
// floor and the wall meeting it are different cells). 32 bits pick the slot, 32 more are kept
// as the key that tells cells sharing a slot apart; linear probing over kRtCacheProbes slots.
//
// Each frame (rt/cache_update.rgen) one pixel in each tile of RtPush::cacheTile^2 pixels
// starts a path of up to RtPush::cacheBounces cosine-distributed rays; every vertex's sample
// of C (the light its next vertex sends back) goes to its cell and to its coarse cell (a hit
// whose cell is empty reads the coarse one): the path's last vertex takes its incoming light
// from the cache itself, so light keeps bouncing from frame to frame. The paths go on through
// surfaces seen on screen (last frame's image is itself still converging, and fed back it
// slowed the cache down: docs/accuracy.md).
// rt.cache.accumulate adds the samples into fixed-point sums (atomics of uint: portable,
// order-independent), rt.cache.resolve blends each cell's mean into its radiance with a
// history of at most RtCachePush::maxSamples samples, so light that went away leaves.
#ifndef TL_SHARED_RT_CACHE_H
#define TL_SHARED_RT_CACHE_H
#include "common.h"
#include "sampling.h"

TL_BEGIN
TL_CONST uint kRtCacheProbes = 8u;        // slots tried from a cell's hash before giving up
TL_CONST uint kRtCacheMaxLevel = 20u;     // cells grow up to kRtCacheCellSize * 2^20
TL_CONST uint kRtCacheCoarseLevels = 2u;  // a sample's coarse cell: 2^2 times its own cell's size
TL_CONST uint kRtCacheMaxBounces = 8u;    // longest update path (rays)
TL_CONST uint kRtCacheMaxAge = 120u;      // frames a cell with no new sample is kept
// A cell's history also fades with time: its weight falls by 1/kRtCacheHistoryFrames a frame,
// so a cell sampled rarely forgets the samples taken while the cache was still filling (whose
// last vertices found nothing to read: a cold start is biased dark) within a few such spans.
// The cache reaches its fixed point (every bounce) like a damped iteration: each frame a cell
// moves about 1/kRtCacheHistoryFrames of the way, and the bounces it reads through its path's
// last vertex are worth rho^k of that; in a closed white box (rho = 0.8) 8 frames left the
// cache 9% short after 64 frames, 4 frames 3% (docs/accuracy.md).
TL_CONST float kRtCacheHistoryFrames = 4.0f;
// Fixed point: a sample at the bound (RtCachePush::bound) is 2^22; at most kRtCacheSampleCap
// samples a frame per cell are summed, so a sum never overflows 32 bits.
TL_CONST float kRtCacheFixedOne = 4194304.0f;
TL_CONST uint kRtCacheSampleCap = 512u;

// What the first ray of an update path found (rt.cache.outcomes, one RtCacheOutcome per path)
// and the light the cache adds there: whether the cache runs is decided from that light.
TL_CONST uint kRtCacheOutcomeNone = 0u;       // no path (the tile's pixel shows the sky)
TL_CONST uint kRtCacheOutcomeSky = 1u;        // the ray left the scene
TL_CONST uint kRtCacheOutcomeOnScreen = 2u;   // it hit a surface seen on screen last frame
TL_CONST uint kRtCacheOutcomeOffScreen = 3u;  // it hit a surface off screen: what the cache serves
TL_CONST uint kRtCacheOutcomeEnded = 4u;      // its length ran out inside the scene: only the cache knows what is there

// One update path's first ray, std430. `gathered` is the luminance of the light the pixel's GI
// ray brings back without the cache (the sky, last frame's image on screen, or a hit lit
// afresh: its direct light and the sky it sees); `added` what the cache adds to it at a hit
// off screen: the hit's albedo times the light arriving there from the next surface its path
// meets (that surface's direct light while the cache is off: the second bounce, a lower
// bound; with the cache on, every bounce the path and the cache hold). Sky reaching the hit
// is counted in `gathered`, as the hit's own sky ray sees it.
struct RtCacheOutcome {
  uint outcome;  // kRtCacheOutcome*
  float gathered;
  float added;
  uint pad0;
};

// One cell's accumulation this frame and the next (by the cache's frame parity), std430.
struct RtCacheAccum {
  uint key;    // 0: empty slot
  uint stamp;  // the cache frame of its last sample (cells without samples for kRtCacheMaxAge go)
  uint pad0;
  uint pad1;
  uint sum[8];  // by frame parity p: [4p + 0..2] fixed-point rgb sums, [4p + 3] samples (plain uints: atomics)
};
// One cell as hits read it, std430.
struct RtCacheEntry {
  vec4 radiance;  // rgb: C (mean incoming radiance over the cosine lobe), w: samples in its history
  uint key;       // the accumulation's key it was resolved from; 0: empty
  uint pad0;
  uint pad1;
  uint pad2;
};
// One path vertex's sample, std430.
struct RtCacheSample {
  uvec4 cell;     // x: slot hash, y: key (0: no sample); zw: the same of its coarse cell
  vec4 radiance;  // rgb: the incoming radiance sampled at the vertex
};

struct RtCachePush {
  uint entryMask;     // entries - 1 (a power of two)
  uint frame;         // the cache's own frame counter (parity picks the sum)
  uint sampleCount;   // samples in rt.cache.samples
  uint restart;       // 1: drop everything (first frame, new scene, the light changed)
  float bound;        // radiance of one sample is clamped to this (fixed point's range)
  float maxSamples;   // history: a cell's radiance averages at most this many samples
  uint maxAge;        // frames without a sample after which a cell is dropped
  float historyDecay; // a cell's history weight is multiplied by this every frame (1 - 1/kRtCacheHistoryFrames)
};

// The level of a cell at `distance` from the camera: the smallest L with
// cellSize * 2^L >= cellAngle * distance.
TL_FN uint tlRtCacheLevel(float distance, float cellSize, float cellAngle) {
  float r = distance * cellAngle / max(cellSize, 1e-9f);
  if (r <= 1.0f) return 0u;
  return min(uint(ceil(log2(r))), kRtCacheMaxLevel);
}
// 0..5: +x, -x, +y, -y, +z, -z by the dominant axis of `n`.
TL_FN uint tlRtCacheNormalBucket(vec3 n) {
  float ax = abs(n.x), ay = abs(n.y), az = abs(n.z);
  if (ax >= ay && ax >= az) return n.x >= 0.0f ? 0u : 1u;
  if (ay >= az) return n.y >= 0.0f ? 2u : 3u;
  return n.z >= 0.0f ? 4u : 5u;
}
// The cell of a world position at `level`: x the slot hash, y the key (never 0).
TL_FN uvec2 tlRtCacheCellAtLevel(vec3 world, vec3 normal, uint level, float cellSize) {
  float size = cellSize * exp2(float(level));
  ivec3 c = ivec3(floor(world / size));
  uint tag = tlPcgHash(level * 6u + tlRtCacheNormalBucket(normal) + 1u);
  uvec3 h = tlPcg3d(uvec3(uint(c.x), uint(c.y), uint(c.z) ^ tag));
  uint key = h.y ^ tlPcgHash(h.z);
  return uvec2(h.x, key == 0u ? 1u : key);
}
// The cell of a world position at `distance` from the camera: x the slot hash, y the key.
TL_FN uvec2 tlRtCacheCell(vec3 world, vec3 normal, float distance, float cellSize, float cellAngle) {
  return tlRtCacheCellAtLevel(world, normal, tlRtCacheLevel(distance, cellSize, cellAngle), cellSize);
}
// The coarse cell holding it, kRtCacheCoarseLevels levels up: every sample goes to both, and a
// hit whose own cell holds nothing reads this one, which holds 4^kRtCacheCoarseLevels times
// as many samples (a hit finding nothing would lose every bounce beyond it).
TL_FN uvec2 tlRtCacheCoarseCell(vec3 world, vec3 normal, float distance, float cellSize, float cellAngle) {
  return tlRtCacheCellAtLevel(world, normal, tlRtCacheLevel(distance, cellSize, cellAngle) + kRtCacheCoarseLevels, cellSize);
}

// A sample in fixed point: clamped to the bound, rounded stochastically by `u` in [0, 1)
// (floor(x + u) has the mean x), so dark cells keep their light in the sum.
TL_FN uint tlRtCacheToFixed(float value, float bound, float u) {
  float x = clamp(value / max(bound, 1e-30f), 0.0f, 1.0f) * kRtCacheFixedOne;
  return uint(floor(x + u));
}
TL_FN float tlRtCacheFromFixed(uint sum, float bound) { return float(sum) * (max(bound, 1e-30f) / kRtCacheFixedOne); }

// A cell's history after a frame with `n` new samples of mean `mean`: its weight (w, in
// samples) first fades by `decay`, then a running mean over at most `maxSamples` samples
// (exponential beyond). Without samples the value stays, only its weight fades.
TL_FN vec4 tlRtCacheBlend(vec4 history, vec3 mean, float n, float maxSamples, float decay) {
  float faded = history.w * decay;
  if (n <= 0.0f) return vec4(history.x, history.y, history.z, faded);
  float w = min(faded + n, max(maxSamples, n));
  vec3 old = vec3(history.x, history.y, history.z);
  vec3 blended = old + (mean - old) * (n / w);
  return vec4(blended.x, blended.y, blended.z, w);
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::RtCacheAccum) == 48);
static_assert(sizeof(tl::shared::RtCacheEntry) == 32);
static_assert(sizeof(tl::shared::RtCacheSample) == 32);
static_assert(sizeof(tl::shared::RtCachePush) == 32);
#endif
#endif
