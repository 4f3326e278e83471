#version 460
// Temporal accumulation of the ray-traced reflections (shared/rt_specular.h), apart from the
// diffuse one: a reflection moves with what it reflects, not with the surface.
//  - Reprojection by the virtual position (RE ENGINE's planar virtual motion): the reflected
//    point seen "behind" a planar reflector lies on the view ray at the surface's distance plus
//    the hit distance; reprojecting that point finds last frame's pixel that showed the same
//    reflection. Rough lobes blur the reflection over hit distance x roughness, where the
//    surface's own motion is the better guess: the two are mixed by roughness.
//  - The history must belong to the same surface (last frame's view depth, as the diffuse
//    temporal checks), else the surface motion's pixel, else none.
//  - Colour clamping: the history is clamped into this frame's neighbourhood (mean +- k
//    standard deviations of the 3x3 samples on the same surface), so content that moved in a
//    mirror does not leave a ghost; on the mirror path a hit distance that changed twofold
//    drops the history; a change of light resets the weight.
//  - Average with weight 1 / n, n growing to the window (RtSpecularPush::maxFrames).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/rt.h"
#include "shared/rt_specular.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kRtBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kRtBindingSpecularMotion) uniform sampler2D gMotion;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtBindingPreviousViewDepth) uniform sampler2D historyDepth;
layout(set = 0, binding = kRtBindingSpecularRaw) uniform sampler2D raw;
layout(set = 0, binding = kRtBindingSpecularHistory) uniform sampler2D history;
layout(set = 0, binding = kRtBindingSpecularHistoryHit) uniform sampler2D historyHit;
layout(set = 0, binding = kRtBindingSpecularAccumulated, rgba16f) uniform writeonly image2D outAccumulated;
layout(set = 0, binding = kRtBindingSpecularHit, r16f) uniform writeonly image2D outHit;
layout(push_constant) uniform SpecularPush { RtSpecularPush sp; };

#include "common/camera.glsl"

// Last frame's uv of a camera-relative point (or of a direction, w = 0: a point at infinity),
// and its view distance then; false off screen or behind the camera.
bool previousUv(vec4 point, out vec2 uv, out float w) {
  vec4 clip = frame.prevViewProj * point;
  uv = vec2(-1.0);
  w = 0.0;
  if (clip.w <= 0.0) return false;
  uv = clip.xy / clip.w * 0.5 + 0.5;
  w = viewWOfClip(clip);
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)));
}

// Whether last frame's pixel at uv showed a surface at view distance near `expected` (within
// `tolerance` of it).
bool sameSurface(vec2 uv, float expected, float tolerance) {
  float w = texelFetch(historyDepth, ivec2(uv * frame.viewport.xy), 0).r;
  return w > 0.0 && abs(w - expected) <= tolerance * expected;
}

// Last frame's accumulation at `uv`, bilinear over the texels that held one (frames > 0): an
// untraced neighbour (a rough or non-reflecting surface, the sky) holds zeros, and a plain
// bilinear fetch would blend them into the history a little every frame wherever the
// reprojection is not exactly on a texel centre (a reflector's edges), a bias that settles
// nowhere. False where none of the four held one.
bool historyAt(vec2 uv, out vec4 accumulated, out float hit) {
  vec2 texel = uv * frame.viewport.xy - 0.5;
  ivec2 base = ivec2(floor(texel));
  vec2 f = texel - vec2(base);
  ivec2 size = ivec2(frame.viewport.xy);
  accumulated = vec4(0.0);
  hit = 0.0;
  float total = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      ivec2 q = base + ivec2(x, y);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 h = texelFetch(history, q, 0);
      if (!(h.a > 0.0)) continue;
      float w = (x == 1 ? f.x : 1.0 - f.x) * (y == 1 ? f.y : 1.0 - f.y);
      accumulated += w * h;
      hit += w * texelFetch(historyHit, q, 0).r;
      total += w;
    }
  if (!(total > 1e-4)) return false;
  accumulated /= total;
  hit /= total;
  return true;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 sample0 = texelFetch(raw, p, 0);
  float depth = texelFetch(gDepth, p, 0).r;
  float roughness = clamp(texelFetch(gMaterial, p, 0).x, 0.0, 1.0);
  vec2 thresholds = tlRtSpecularRoughness(sp.specularRoughness);
  bool mirror = tlRtSpecularIsMirror(roughness, thresholds.y);
  // No ray this frame: untraced (rough, non-reflecting, the sky), or a reflecting pixel the
  // rough checkerboard skipped (it takes its history, or its traced neighbours).
  bool skipped = depth > 0.0 && sample0.a <= kRtSpecularNotTraced && !mirror &&
                 tlRtSpecularTracedWeight(roughness, thresholds.x) > 0.0 &&
                 tlRtSpecularSkipsFrame(uint(p.x), uint(p.y), frame.frameIndex, sp.roughDivisor);
  if (depth <= 0.0 || (sample0.a <= kRtSpecularNotTraced && !skipped)) {
    imageStore(outAccumulated, p, vec4(0.0));
    imageStore(outHit, p, vec4(0.0));
    return;
  }
  // This frame's neighbourhood on the same surface: the clamp's range.
  vec3 sum = vec3(0.0), sumSquares = vec3(0.0);
  float count = 0.0, hitSum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(p + ivec2(x, y), ivec2(0), size - 1);
      vec4 s = texelFetch(raw, q, 0);
      float d = texelFetch(gDepth, q, 0).r;
      if (s.a <= kRtSpecularNotTraced || d <= 0.0 || abs(d - depth) > 0.05 * depth) continue;
      sum += s.rgb;
      sumSquares += s.rgb * s.rgb;
      count += 1.0;
      hitSum += s.a;
    }
  vec3 mean = sum / max(count, 1.0);
  vec3 sigma = sqrt(max(sumSquares / max(count, 1.0) - mean * mean, vec3(0.0)));
  if (skipped) {
    if (count == 0.0) {  // no traced neighbour on this surface either
      imageStore(outAccumulated, p, vec4(0.0));
      imageStore(outHit, p, vec4(0.0));
      return;
    }
    sample0 = vec4(mean, hitSum / count);  // stands in for the reprojection; its colour only without a history
  }

  vec3 position = pixelPosition(p, depth);
  float traced = max(thresholds.x, 1e-4);
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  vec2 surfaceUv = uv - texelFetch(gMotion, p, 0).xy;
  float expected = viewWOfClip(frame.prevViewProj * vec4(position, 1.0));
  bool surfaceValid = all(greaterThanEqual(surfaceUv, vec2(0.0))) && all(lessThan(surfaceUv, vec2(1.0))) &&
                      sameSurface(surfaceUv, expected, 0.05);
  // The virtual point: on the view ray, the hit distance beyond the surface (a miss: at infinity).
  float hitDistance = sample0.a;
  vec3 away = -towardsViewer(position);
  vec4 virtualPoint = hitDistance >= kRtMaxHitDistance ? vec4(away, 0.0) : vec4(position + away * hitDistance, 1.0);
  vec2 virtualUv;
  float virtualW;
  bool virtualValid = previousUv(virtualPoint, virtualUv, virtualW);
  float mirrorLike = 1.0 - clamp(roughness / traced, 0.0, 1.0);
  vec2 historyUv = virtualValid ? mix(surfaceUv, virtualUv, mirrorLike) : surfaceUv;
  bool valid = sp.historyValid != 0u && surfaceValid;
  // The virtual pixel must still lie on this surface (at a reflector's edge, the surface's own).
  if (valid && !sameSurface(historyUv, expected, 0.1)) historyUv = surfaceUv;
  vec4 previous = vec4(0.0);
  float previousHit = 0.0;
  if (valid) valid = historyAt(historyUv, previous, previousHit);
  if (!all(lessThan(abs(previous), vec4(1e30)))) previous = vec4(0.0);
  float frames = valid ? previous.a : 0.0;
  if (sp.lightChanged != 0u) frames = min(frames, 1.0);
  // Clamp what the history remembers into what this frame sees around the pixel.
  vec3 remembered = clamp(previous.rgb, mean - sp.clampSigma * sigma, mean + sp.clampSigma * sigma);
  // A mirror's ray is the same every frame: where its hit distance is more than twice the
  // history's, or under half of it, something moved into or out of the reflection, and the
  // history goes. (At a reflection's edges the colour clamp's 3x3 holds both sides and cannot
  // tell: the box arriving on mirror_floor's mirror left a 16-frame ghost outline.) A rough
  // lobe's rays differ from frame to frame, and a lobe that straddles two objects changes its
  // distance every frame: there the test would only throw history away (the metal furnace's
  // worst pixel went from 0.06 to 0.27), so rough lobes rely on the clamp.
  if (mirror && frames > 0.0 && (hitDistance > 2.0 * previousHit || previousHit > 2.0 * hitDistance)) frames = 0.0;
  // A skipped pixel with a history keeps it as it is, and its count (the next frame traces it
  // and clamps it: clamping on skipped frames too, against half the neighbours, blurred the
  // image: relMSE_norm against the full rate 5.8x the noise between two full-rate images);
  // without one it starts from its traced neighbours' mean, as one frame's worth.
  float n = skipped && frames > 0.0 ? frames : min(frames + 1.0, max(sp.maxFrames, 1.0));
  vec3 accumulated = skipped && frames > 0.0 ? previous.rgb : mix(remembered, sample0.rgb, 1.0 / n);
  float meanHit = skipped && frames > 0.0 ? previousHit
                  : frames > 0.0          ? mix(previousHit, min(hitDistance, kRtMaxHitDistance), 1.0 / n)
                                          : hitDistance;
  imageStore(outAccumulated, p, vec4(accumulated, n));
  imageStore(outHit, p, vec4(min(meanHit, kRtMaxHitDistance), 0.0, 0.0, 0.0));
}
