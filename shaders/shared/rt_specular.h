// Ray-traced reflections of the RT path (engine/lighting/rt/, shaders/rt/specular*), after
// RE ENGINE (2023): a pixel whose roughness is below RtPush's traced threshold takes one
// specular ray per frame, drawn from the GGX visible normals (shared/microfacet.h), whose hit is
// lit as the GI rays' hits are (rt/hit_lighting.glsl). Below the mirror threshold the ray is the
// perfect reflection and the image is not filtered across pixels (RE ENGINE's mirror path).
//
// Demodulation. A sample of incoming radiance L along l drawn from the visible normals carries
// the single-scattering lobe's weight f_ss cos / pdf = F(v.h) G2(l, v) / G1(v), whose mean over
// the lobe is the lobe's directional albedo E_ss(mu_o) = F0 S + B (the split tables,
// shared/shading.h). The passes store and filter L times that weight divided by E_ss: the
// lobe-weighted mean of the light the lobe sees, a radiance independent of the material's
// colour, so neighbours of other colours and F0 filter together. The composite multiplies it
// back by the whole specular albedo (tlEnvironmentSpecular: single + multiple scattering), so
// the multiple-scattering lobe is taken to see the same light as the single one (exact under
// uniform light, and a few percent of the specular below the traced roughness). A white metal
// under a uniform sky shows exactly the sky: the furnace holds.
//
// The seam with the SH specular (shared/sh_specular.h) above the threshold: over the top fifth
// of the traced roughness range the composite blends from the traced estimate to the SH's, so a
// roughness ramp shows no step (both estimate the same quantity; the SH's is the less exact).
// Shared by C++ (tests) and GLSL.
#ifndef TL_SHARED_RT_SPECULAR_H
#define TL_SHARED_RT_SPECULAR_H
#include "common.h"
#include "packing.h"

TL_BEGIN
// The share of the traced roughness range over which the composite blends into the SH specular.
TL_CONST float kRtSpecularSeamWidth = 0.2f;

// RtPush::specularRoughness: the two thresholds as halves (x traced below, y mirror below).
TL_FN uint tlRtPackSpecularRoughness(float traced, float mirror) {
  return tlPackHalf2x16(vec2(clamp(traced, 0.0f, 1.0f), clamp(mirror, 0.0f, 1.0f)));
}
TL_FN vec2 tlRtSpecularRoughness(uint packed) { return tlUnpackHalf2x16(packed); }

// The weight of the traced specular at a roughness: 1 well below the threshold, 0 at and
// above it, linear over the seam (a threshold of 0 traces nothing).
TL_FN float tlRtSpecularTracedWeight(float roughness, float threshold) {
  if (!(threshold > 0.0f)) return 0.0f;
  float seam = kRtSpecularSeamWidth * threshold;
  return clamp((threshold - roughness) / seam, 0.0f, 1.0f);
}

// The mirror path: the material's roughness (the G-buffer's, before the BRDF's floor of
// kBrdfMinRoughness, which lies above the default threshold) at or below the mirror threshold
// (0: none). Every pass asks with the same value.
TL_FN bool tlRtSpecularIsMirror(float roughness, float mirrorThreshold) { return roughness <= mirrorThreshold; }

// One visible-normal sample's demodulated weight per channel: F(v.h) G2 / G1 over E_ss(mu_o)
// (`singleAlbedo`, per channel: F0 S + B). Its mean over the lobe is 1.
TL_FN vec3 tlRtSpecularSampleWeight(vec3 fresnel, float g2OverG1, vec3 singleAlbedo) {
  return fresnel * g2OverG1 / max(singleAlbedo, vec3(1e-4f));
}

// Whether a lobe reflects enough to be worth a ray: its single-scattering albedo (per channel)
// reaches 1/1024 in some channel, under a quarter of an 8-bit display step of what it reflects.
// Below it (specularFactor 0, an IOR near 1) the SH specular shades the pixel: a sample's weight
// would divide one tiny number by another (the albedo table's interpolation error then dominates),
// and the spatial filter would spread those values into coplanar neighbours of other materials.
TL_CONST float kRtSpecularMinAlbedo = 1.0f / 1024.0f;
TL_FN bool tlRtSpecularWorthTracing(vec3 singleAlbedo) {
  return max(max(singleAlbedo.x, singleAlbedo.y), singleAlbedo.z) >= kRtSpecularMinAlbedo;
}

// The rough reflections' checkerboard (rtReflectionRoughDivisor 2): a reflecting pixel above
// the mirror threshold traces on the frames where x + y + frame is even, as the GI's
// checkerboard does; on the others the temporal pass keeps its history (clamped by the traced
// neighbours) or, without one, takes the traced neighbours' mean. Mirrors trace every frame.
TL_FN bool tlRtSpecularSkipsFrame(uint x, uint y, uint frameIndex, uint roughDivisor) {
  return roughDivisor >= 2u && ((x + y + frameIndex) & 1u) != 0u;
}

// The hit distance stored for a pixel that traced no specular ray this frame (a traced ray's
// is at least RtPush::tMin > 0, a miss's kRtMaxHitDistance): every value stays >= 0.
TL_CONST float kRtSpecularNotTraced = 0.0f;

// The specular temporal pass and filter's own push constants.
struct RtSpecularPush {
  uint historyValid;     // 0: the history holds nothing usable
  float maxFrames;       // the accumulation's window (frames)
  float clampSigma;      // the history is clamped to this many standard deviations of this frame's neighbourhood
  uint specularRoughness;// RtPush::specularRoughness (half2: traced below, mirror below)
  float rotation;        // the filter's Poisson disk rotation this frame (radians)
  float maxRadius;       // the filter's largest radius, pixels
  uint lightChanged;     // 1: the light changed: the history keeps one frame's weight
  uint roughDivisor;     // 2: rough (non-mirror) pixels trace on a checkerboard (tlRtSpecularSkipsFrame)
};

// Bindings (set 0) beyond the RT path's (shared/rt.h).
TL_CONST uint kRtBindingSpecularRaw = 41;           // rgba16f: demodulated radiance of this frame's ray (rgb), hit distance (a; 0 untraced)
TL_CONST uint kRtBindingSpecularHistory = 42;       // rgba16f: last frame's accumulation (rgb), frames (a)
TL_CONST uint kRtBindingSpecularHistoryHit = 43;    // r16f: last frame's accumulated hit distance
TL_CONST uint kRtBindingSpecularAccumulated = 44;   // rgba16f: this frame's accumulation
TL_CONST uint kRtBindingSpecularHit = 45;           // r16f: this frame's accumulated hit distance
TL_CONST uint kRtBindingSpecularFiltered = 46;      // rgba16f: filtered (rgb), traced weight (a)
TL_CONST uint kRtBindingSpecularMotion = 47;        // gbuffer.motion
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::RtSpecularPush) == 32);
#endif
#endif
