#version 460
// Temporal accumulation of the RT path's raw SH irradiance and AO, before any spatial
// filtering (Metro Exodus): reproject with the motion vectors, reject history that falls
// off screen or belongs to another surface (view-depth test), and average with weight
// 1 / n, n growing to maxAccumFrames. Linear space throughout, with RE ENGINE's guards in
// place of a Reinhard curve: non-finite samples are dropped, fireflies are scaled down to a
// multiple of their neighbourhood's or history's RMS (optional: see shared/rt.h), and when
// the light changed the history is clipped to this frame's samples (luminance rejection).
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"
#include "shared/sampling.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtTemporalMotion) uniform sampler2D gMotion;
layout(set = 0, binding = kRtTemporalRawShY) uniform sampler2D rawShY;
layout(set = 0, binding = kRtTemporalRawCoCg) uniform sampler2D rawCoCg;
layout(set = 0, binding = kRtTemporalRawAo) uniform sampler2D rawAo;
layout(set = 0, binding = kRtTemporalHistoryShY) uniform sampler2D historyShY;
layout(set = 0, binding = kRtTemporalHistoryCoCgAo) uniform sampler2D historyCoCgAo;
layout(set = 0, binding = kRtTemporalHistoryViewDepth) uniform sampler2D historyDepth;
layout(set = 0, binding = kRtTemporalOutShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kRtTemporalOutCoCgAo, rgba16f) uniform writeonly image2D outCoCgAo;
layout(set = 0, binding = kRtTemporalOutViewDepth, r32f) uniform writeonly image2D outDepth;
layout(set = 0, binding = kRtTemporalHistoryMoment) uniform sampler2D historyMoment;
// x: the mean squared sample luma; y: the mean inverse hit distance (the denoiser's radius).
layout(set = 0, binding = kRtTemporalOutMoment, rg32f) uniform writeonly image2D outMoment;

// How much the view depth changes over one pixel on this pixel's surface: per axis the
// smaller step to the two opposite neighbours (the plane's gradient; the larger one may cross
// an edge), the larger of the two axes. Neighbours more than 10% away do not count.
float depthStep(ivec2 p, float w, ivec2 size) {
  float step = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    ivec2 e = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    float smallest = 1e30;
    for (int side = -1; side <= 1; side += 2) {
      ivec2 q = clamp(p + side * e, ivec2(0), size - 1);
      float d = texelFetch(gDepth, q, 0).r;
      if (d <= 0.0 || q == p) continue;
      float dw = abs(depthToViewW(d) - w);
      if (dw < 0.1 * w) smallest = min(smallest, dw);
    }
    if (smallest < 1e30) step = max(step, smallest);
  }
  return step;
}

// This frame's samples around p on the same surface (depth within 5%): the ceiling above
// which a sample is a firefly, and the range of the samples once clipped to it. Only pixels
// that traced this frame count; with fewer rays per pixel the window widens to 5x5 so it
// still holds several.
//
// The ceiling (shared/rt.h tlRtFireflyCeiling) is k times an RMS: the pixel's history's, or
// its neighbours' leaving out the largest sample (one spike must not raise its own limit).
struct Neighbourhood {
  float ceiling;        // firefly ceiling on a sample's luma (SH L0); huge when off
  float lowest;         // smallest and largest luma of the clipped samples
  float highest;
  int count;
};
Neighbourhood neighbourhood(ivec2 p, float depth, ivec2 size, float historyRms) {
  const int kMax = 25;
  float luma[kMax];
  int count = 0;
  float sumSquares = 0.0, largest = 0.0;
  int radius = push.rayPattern == kRtRaysFull ? 1 : 2;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) {
      ivec2 q = p + ivec2(x, y);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      if (!tlRtTracesThisFrame(q, frame.frameIndex, push.rayPattern)) continue;
      float d = texelFetch(gDepth, q, 0).r;
      if (d <= 0.0 || abs(d - depth) > 0.05 * depth) continue;
      float l = texelFetch(rawShY, q, 0).x;
      if (isnan(l) || isinf(l)) continue;
      l = max(l, 0.0);
      luma[count++] = l;
      sumSquares += l * l;
      largest = max(largest, l);
    }
  Neighbourhood n;
  n.ceiling = kRtNoCeiling;
  n.lowest = 0.0;
  n.highest = 0.0;
  n.count = count;
  if (count == 0) return n;
  float trimmedRms = count > 1 ? sqrt(max(sumSquares - largest * largest, 0.0) / float(count - 1)) : 0.0;
  n.ceiling = tlRtFireflyCeiling(trimmedRms, historyRms, push.fireflyClamp);
  n.lowest = 1e30;
  for (int i = 0; i < count; ++i) {
    float l = min(luma[i], n.ceiling);
    n.lowest = min(n.lowest, l);
    n.highest = max(n.highest, l);
  }
  return n;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  ivec2 src = p;
  bool noSample = false;  // half resolution: no traced sample nearby this frame (keep the history)
  if (push.rayPattern == kRtRaysCheckerboard && !tlRtTracesThisFrame(p, frame.frameIndex, push.rayPattern)) {
    // 0.5 rays per pixel: a pixel without a ray this frame takes its horizontal neighbour's
    // sample (which had one) when that neighbour is the same surface, else the vertical one.
    ivec2 a = ivec2(p.x ^ 1, p.y), b = ivec2(p.x, p.y ^ 1);
    a = min(a, size - 1);
    b = min(b, size - 1);
    float da = abs(texelFetch(gDepth, a, 0).r - depth), db = abs(texelFetch(gDepth, b, 0).r - depth);
    src = da <= db ? a : b;
  } else if (push.rayPattern == kRtRaysHalfResolution && !tlRtTracesThisFrame(p, frame.frameIndex, push.rayPattern)) {
    // Half resolution, depth-aware noisy upsampling (INSIDE): of the four traced samples
    // around the pixel (its own 2x2 block and the three towards its side), pick one at random
    // with a probability that falls with the depth difference. The noise averages out in the
    // accumulation below; always taking the nearest would freeze blocks into the image.
    ivec2 own = (p & ~1) + tlRtBlockOffset(frame.frameIndex);
    ivec2 side = ivec2((p.x & 1) == 1 ? 2 : -2, (p.y & 1) == 1 ? 2 : -2);
    ivec2 candidates[4] = ivec2[4](own, own + ivec2(side.x, 0), own + ivec2(0, side.y), own + side);
    float weights[4];
    float total = 0.0;
    for (int i = 0; i < 4; ++i) {
      // Outside the image there is no traced sample (clamping would land on an untraced pixel).
      ivec2 c = candidates[i];
      bool inside = all(greaterThanEqual(c, ivec2(0))) && all(lessThan(c, size));
      float d = inside ? texelFetch(gDepth, c, 0).r : 0.0;
      float rel = abs(d - depth) / max(depth, 1e-6);
      weights[i] = d > 0.0 ? 1.0 / (1e-3 + rel * rel * 1e4) : 0.0;
      total += weights[i];
    }
    if (total <= 0.0) noSample = true;
    // A hash of pixel and frame chooses (uniform in [0, total)).
    float u = tlUintToUnitFloat(tlPcg3d(uvec3(uvec2(p), frame.frameIndex)).x) * total;
    // Rounding may leave u past the last weight: fall back to the heaviest candidate (inside).
    int heaviest = 0;
    for (int i = 1; i < 4; ++i)
      if (weights[i] > weights[heaviest]) heaviest = i;
    src = candidates[heaviest];
    for (int i = 0; i < 4; ++i) {
      if (weights[i] > 0.0 && u < weights[i]) {
        src = candidates[i];
        break;
      }
      u -= weights[i];
    }
  }
  vec4 shY = noSample ? vec4(0.0) : texelFetch(rawShY, src, 0);
  vec2 aoHit = noSample ? vec2(1.0, push.hitDistanceCap) : texelFetch(rawAo, src, 0).rg;
  vec4 coCgAo = noSample ? vec4(0.0, 0.0, 1.0, 0.0) : vec4(texelFetch(rawCoCg, src, 0).xy, aoHit.x, 1.0);
  // The inverse of the hit distance averages to the harmonic mean: near occluders dominate it,
  // as they dominate how fast the irradiance changes across the surface. A miss, or a hit beyond
  // the denoiser's radius, limits nothing (0); a contact closer than a twentieth of it counts
  // as that twentieth, so one corner sample does not pin the radius to nothing.
  float inverseHit = aoHit.y < push.hitDistanceCap ? 1.0 / max(aoHit.y, 0.05 * push.hitDistanceCap) : 0.0;
  if (!finite4(shY) || !finite4(coCgAo)) {  // a broken sample never reaches the history
    noSample = true;
    shY = vec4(0.0);
    coCgAo = vec4(0.0, 0.0, 1.0, 0.0);
  }
  if (depth <= 0.0) {
    imageStore(outShY, p, vec4(0.0));
    imageStore(outCoCgAo, p, vec4(0.0, 0.0, 1.0, 0.0));
    imageStore(outDepth, p, vec4(0.0));
    imageStore(outMoment, p, vec4(0.0));
    return;
  }
  vec3 position = pixelPosition(p, depth);
  float w = viewW(position);
  // The history at this surface's position last frame, if it is the same surface.
  bool hasHistory = false;
  vec4 historySh = vec4(0.0), history = vec4(0.0);
  float meanSquare = 0.0;  // the history's mean squared sample luma
  float meanInverseHit = 0.0;  // and its mean inverse hit distance
  if (push.historyValid != 0u) {
    vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
    vec2 previousUv = uv - texelFetch(gMotion, p, 0).xy;
    // Where this surface was last frame, and how far from the camera it was then.
    vec4 previousClip = frame.prevViewProj * vec4(position, 1.0);
    bool onScreen = all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0)));
    if (onScreen && previousClip.w > 0.0) {
      ivec2 q = ivec2(previousUv * frame.viewport.xy);
      float historyW = texelFetch(historyDepth, q, 0).r;
      history = texelFetch(historyCoCgAo, q, 0);
      // The history texel's centre lies up to a pixel from this surface point (sub-pixel
      // motion, TAA's jitter): on a grazing surface that alone moves the depth by its
      // gradient, so the tolerance grows with this pixel's depth step to its neighbours.
      float previousW = viewWOfClip(previousClip);
      bool sameSurface = historyW > 0.0 && abs(historyW - previousW) <= 0.03 * previousW + depthStep(p, w, size);
      hasHistory = sameSurface && history.w >= 1.0;
      if (hasHistory) {
        historySh = texelFetch(historyShY, q, 0);
        vec2 moments = texelFetch(historyMoment, q, 0).xy;
        meanSquare = moments.x;
        meanInverseHit = moments.y;
      }
    }
  }
  // The neighbourhood serves only the firefly clamp and a change of light: otherwise it is not
  // read (up to 25 depth and SH fetches a pixel, a third of this pass on lavapipe).
  Neighbourhood nb;
  nb.ceiling = kRtNoCeiling;
  nb.count = 0;
  if (push.fireflyClamp > 0.0 || push.lightChanged != 0u)
    nb = neighbourhood(p, depth, size, hasHistory ? sqrt(max(meanSquare, 0.0)) : 0.0);
  if (!noSample && shY.x > nb.ceiling) {
    float k = nb.ceiling / shY.x;  // scale the whole sample: its direction and colour stay
    shY *= k;
    coCgAo.xy *= k;
  }
  float shY0 = max(shY.x, 0.0);  // this frame's (clipped) sample luma
  if (hasHistory && push.lightChanged != 0u) {
    // Luminance rejection: the history keeps its direction and colour at a luma inside this
    // frame's range (where there are samples to say so), and only a couple of frames' weight,
    // whether the light went off (clipped down) or came on over a dark history (capped).
    if (nb.count > 0 && historySh.x > 0.0) {
      float k = clamp(historySh.x, nb.lowest, nb.highest) / historySh.x;
      historySh *= k;
      history.xy *= k;
      meanSquare *= k * k;
    }
    history.w = min(history.w, kRtLightChangeFrames);
  }
  if (hasHistory && noSample) {  // nothing new this frame: the (rectified) history as it is
    shY = historySh;
    coCgAo = history;
  } else if (hasHistory) {
    float n = min(history.w + 1.0, float(max(push.maxAccumFrames, 1u)));
    float a = 1.0 / n;
    shY = mix(historySh, shY, a);
    coCgAo = vec4(mix(history.xyz, coCgAo.xyz, a), n);
    meanSquare = mix(meanSquare, shY0 * shY0, a);
    meanInverseHit = mix(meanInverseHit, inverseHit, a);
  } else {
    meanSquare = shY0 * shY0;
    meanInverseHit = inverseHit;
  }
  // Rounded here, not by the store: the history must not drift on a device that truncates.
  imageStore(outShY, p, tlRoundToHalf(shY));
  imageStore(outCoCgAo, p, tlRoundToHalf(coCgAo));
  imageStore(outDepth, p, vec4(w));
  imageStore(outMoment, p, vec4(meanSquare, meanInverseHit, 0.0, 0.0));
}
