// The ray-traced lighting path (engine/lighting/rt/, shaders/rt/), after Metro Exodus (GDC 2019):
// the ray generation every stage repeats, the one-uint hit record, the SH sample weight,
// per-instance hit data and the bindings. Shared by C++ (tests) and GLSL.
//
// Hit record: one uint per pixel, written by the pre-trace (G-buffer albedo) or the real
// trace (per-instance albedo), read by hit lighting and RTAO.
//   bits  0..15  hit distance as an IEEE half (sign always 0, so <= 0x7BFF for finite hits);
//                two NaN patterns with the sign set are codes: kRtHitMiss (the ray left the
//                scene) and kRtHitPending (the pre-trace found nothing: trace a real ray). With
//                0.5 rays per pixel the pixels off this frame's checkerboard are not written.
//                Relative error <= 2^-11 for 6.1e-5 m <= d <= 65504 m (half's normal range);
//                below, absolute error <= 2^-25 m; above, clamped to 65504 m.
//   bits 16..31  hit albedo, RGB 5:6:5 of sqrt(albedo) (gamma 2: more codes in the darks).
//                Error per channel <= sqrt(a)/31 + 1/31^2 (R, B) and sqrt(a)/63 + 1/63^2 (G).
//
// Ray generation (tlRtRayDirection): cosine-weighted around the shading normal from a 64x64
// blue-noise texture of two channels, offset per frame by the R2 sequence (Cranley-Patterson
// rotation) so every frame samples new directions with blue-noise spatial structure. The
// pre-trace, the trace and hit lighting call the same function with the same inputs, so
// the ray is regenerated exactly rather than stored.
//
// SH sample weight (tlRtShSampleWeight): a cosine-distributed sample of radiance L from d,
// projected with weight w = pi / (1/4 + cos/2), resolves (shared/sh.h) to exactly pi L at
// the sampling normal: E(n) = w L (1/4 + cos/2). So the mean over samples is an unbiased
// estimate of the irradiance at the pixel's normal, and the L1 band still carries the
// direction light came from (for normal-mapped neighbours, the denoiser, specular). The
// weight stays within [4 pi / 3, 4 pi]: no 1/pdf blow-up at grazing angles.
#ifndef TL_SHARED_RT_H
#define TL_SHARED_RT_H
#include "common.h"
#include "emitters.h"
#include "material_mode.h"
#include "packing.h"
#include "sampling.h"
#include "sh.h"

TL_BEGIN
TL_CONST uint kRtHitMiss = 0xFFFFu;
TL_CONST uint kRtHitPending = 0xFFFEu;
TL_CONST float kRtMaxHitDistance = 65504.0f;
TL_CONST uint kRtBlueNoiseSize = 64u;
// The AO filter: the relative view-depth difference that halves a tap's weight.
TL_CONST float kRtAoFilterDepth = 0.02f;

TL_FN uint tlRtEncodeAlbedo(vec3 albedo) {
  vec3 e = sqrt(clamp(albedo, vec3(0.0f), vec3(1.0f)));
  uint r = uint(e.x * 31.0f + 0.5f), g = uint(e.y * 63.0f + 0.5f), b = uint(e.z * 31.0f + 0.5f);
  return (r << 11u) | (g << 5u) | b;
}
TL_FN vec3 tlRtDecodeAlbedo(uint bits) {
  vec3 e = vec3(float((bits >> 11u) & 31u) / 31.0f, float((bits >> 5u) & 63u) / 63.0f, float(bits & 31u) / 31.0f);
  return e * e;
}

TL_FN uint tlRtPackHit(float distance, vec3 albedo) {
  float d = clamp(distance, 0.0f, kRtMaxHitDistance);
  return (tlPackHalf2x16(vec2(d, 0.0f)) & 0xFFFFu) | (tlRtEncodeAlbedo(albedo) << 16u);
}
TL_FN bool tlRtIsMiss(uint hit) { return (hit & 0xFFFFu) == kRtHitMiss; }
TL_FN bool tlRtIsPending(uint hit) { return (hit & 0xFFFFu) == kRtHitPending; }
TL_FN bool tlRtIsHit(uint hit) { return (hit & 0xFFFFu) < kRtHitPending; }
// Which pixels trace a ray this frame (RtPush::rayPattern).
TL_CONST uint kRtRaysFull = 0u;            // every pixel: 1 ray per pixel
TL_CONST uint kRtRaysCheckerboard = 1u;    // 0.5 rays per pixel: a checkerboard flipped every frame
TL_CONST uint kRtRaysHalfResolution = 2u;  // 0.25: one pixel of each 2x2 block, cycling through all four
// Half resolution: the pixel of each 2x2 block that traces in this frame.
TL_FN ivec2 tlRtBlockOffset(uint frame) {
  uint k = frame & 3u;  // (0,0), (1,1), (1,0), (0,1): opposite corners follow each other
  return ivec2(int(k == 1u || k == 2u), int(k == 1u || k == 3u));
}
TL_FN bool tlRtTracesThisFrame(ivec2 p, uint frame, uint pattern) {
  if (pattern == kRtRaysCheckerboard) return ((uint(p.x + p.y) + frame) & 1u) == 0u;
  if (pattern == kRtRaysHalfResolution) {
    ivec2 o = tlRtBlockOffset(frame);
    return (p.x & 1) == o.x && (p.y & 1) == o.y;
  }
  return true;
}
TL_FN float tlRtHitDistance(uint hit) { return tlUnpackHalf2x16(hit & 0xFFFFu).x; }
TL_FN vec3 tlRtHitAlbedo(uint hit) { return tlRtDecodeAlbedo(hit >> 16u); }

// What a hit reflects of light it receives, as one colour (Metro: albedo (1 - F0) + F0, so
// metals, whose diffuse albedo is zero, still bounce their specular colour).
TL_FN vec3 tlRtHitAlbedoFromMaterial(vec3 baseColor, float metallic) {
  vec3 diffuse = baseColor * (1.0f - metallic);
  vec3 f0 = mix(vec3(0.04f), baseColor, metallic);
  return diffuse * (vec3(1.0f) - f0) + f0;
}

// The hit albedo under a material override mode: the Lambertian modes reflect their albedo.
TL_FN vec3 tlMaterialHitAlbedo(vec3 baseColor, float metallic, uint materials) {
  if (materials == kMaterialsAuthored) return tlRtHitAlbedoFromMaterial(baseColor, metallic);
  return tlMaterialBaseColor(baseColor, materials);
}

// Last frame's shaded radiance at a hit seen on screen, re-coloured to the albedo the hit
// record carries (the per-instance albedo for real rays, the G-buffer's for pre-traced
// ones): the light the surface reflected, divided by the albedo it was shaded with, times
// the record's albedo, plus its emission. So an artist's override or the baked database
// shows in the bounce also where the hit is on screen. Albedos here follow the F0 rule,
// which never goes below 0.04: the ratio stays bounded.
TL_FN vec3 tlRtRecolourScreenRadiance(vec3 seen, vec3 emission, vec3 screenAlbedo, vec3 hitAlbedo) {
  vec3 reflected = max(seen - emission, vec3(0.0f));
  return emission + reflected * (hitAlbedo / max(screenAlbedo, vec3(0.04f)));
}

// Shared-exponent HDR colour in one uint (the RGB9E5 format): emission at hits.
TL_FN uint tlPackRgb9e5(vec3 rgb) {
  const float maxValue = 65408.0f;  // (2^9 - 1) / 2^9 * 2^(31 - 15)
  vec3 c = clamp(rgb, vec3(0.0f), vec3(maxValue));
  float m = max(c.x, max(c.y, c.z));
  if (m < 1e-9f) return 0u;
  int e = max(-16, int(floor(log2(m)))) + 1;  // 2^(e-1) <= m < 2^e
  float scale = exp2(float(9 - e));
  uvec3 q = uvec3(c * scale + vec3(0.5f));
  if (max(q.x, max(q.y, q.z)) >= 512u) {
    e += 1;
    scale *= 0.5f;
    q = uvec3(c * scale + vec3(0.5f));
  }
  return min(q.x, 511u) | (min(q.y, 511u) << 9u) | (min(q.z, 511u) << 18u) | (uint(e + 15) << 27u);
}
TL_FN vec3 tlUnpackRgb9e5(uint p) {
  float scale = exp2(float(int(p >> 27u) - 15 - 9));
  return vec3(float(p & 511u), float((p >> 9u) & 511u), float((p >> 18u) & 511u)) * scale;
}

// The two uniforms of a pixel's ray this frame: its blue-noise value, rotated by R2.
TL_FN vec2 tlRtRandom(vec2 blueNoise, uint frame) {
  vec2 r = blueNoise + float(frame & 4095u) * vec2(0.75487766624669276f, 0.56984029099805327f);
  return r - floor(r);
}
TL_FN vec3 tlRtRayDirection(vec3 normal, vec2 u) { return tlLocalToWorld(tlSampleCosineHemisphere(u), normal); }

TL_FN float tlRtShSampleWeight(float cosTheta) { return kPi / (0.25f + 0.5f * clamp(cosTheta, 0.0f, 1.0f)); }
TL_FN ShLumaCoCg tlRtProjectSample(vec3 normal, vec3 direction, vec3 radiance) {
  return tlShScale(tlShProjectRadiance(direction, radiance), tlRtShSampleWeight(dot(normal, direction)));
}

// Temporal accumulation's guards (rt/temporal.comp), in linear space (RE ENGINE 2023: no
// Reinhard compression, explicit firefly and luminance handling instead).
//
// Firefly suppression: a new sample whose luma (SH L0) exceeds the ceiling is scaled down to
// it (all SH and chroma coefficients alike, so its direction and colour stay). The ceiling
// is k times a root mean square of luma, the larger of the pixel's history's and its
// neighbours' this frame (without their largest): where light arrives through few bright
// rays (hit probability p), a true sample is 1/p times the mean but only 1/sqrt(p) times
// the RMS, so the light is kept while a lone 1e4 spike among ones is cut to k. Without any
// scale (no history, dark neighbours) or with k <= 0 there is no ceiling (kRtNoCeiling).
TL_CONST float kRtNoCeiling = 1e30f;
TL_FN float tlRtFireflyCeiling(float neighbourRms, float historyRms, float k) {
  float scale = max(neighbourRms, historyRms);
  return k > 0.0f && scale > 0.0f ? k * scale : kRtNoCeiling;
}
// Temporal luminance rejection on a change of light (RE ENGINE 2023; its "light buffer
// flags" variant): in the first frame after the sun, the sky, an emitter or an albedo
// changed, each pixel's history luma is clipped into the range of this frame's samples
// around it (a light switched off leaves nothing above zero, so its history goes at once),
// and its frame count is capped at kRtLightChangeFrames so what is left catches up within
// a few frames. A per-pixel statistical test on one ray per pixel cannot tell a light
// switched off from a sparse signal (light through a few rays): every variant tried either
// missed the change or biased the Cornell box by 5-20%; the change itself is known exactly.
TL_CONST float kRtLightChangeFrames = 1.0f;

// Disocclusion rays (RE ENGINE 2023): where this frame rejected the history, one sample is all
// the accumulation has. Each kRtDisocclusionCell x kRtDisocclusionCell cell of the screen with
// such a pixel traces RtPush::disocclusionRays rays (Hammersley points, rotated per cell and
// frame) from one of them, the one nearest the cell's centre, and keeps their mean SH; cells
// without one trace nothing, so a still camera pays almost nothing. Each fresh pixel then takes
// the cells around it that lie on its own plane, as tlRtDisocclusionFrames(rays) frames of
// history: the mean of many rays from a few pixels away, more biased than its own ray (a
// different point, the pixel's normal only through the SH) and far less noisy, which the
// accumulation then replaces as real frames come in.
TL_CONST uint kRtDisocclusionCell = 8u;          // pixels per side of a cell
TL_CONST float kRtDisocclusionFreshFrames = 1.0f; // a pixel with at most this many frames has no history
TL_FN float tlRtDisocclusionFrames(uint rays) { return 0.25f * min(float(rays), 32.0f); }
// The Hammersley point i of n, Cranley-Patterson rotated: a disocclusion ray's two uniforms.
TL_FN vec2 tlRtDisocclusionUniforms(uint i, uint n, vec2 rotation) {
  vec2 u = vec2((float(i) + 0.5f) / float(n), tlRadicalInverse2(i)) + rotation;
  return u - floor(u);
}

// Emitter sampling (next-event estimation, shared/emitters.h): the emissive triangles of the
// scene, one chosen in proportion to its power from the alias table the reference draws from
// too, a point uniform on it, a shadow ray to it. With it on, rays that hit an emitter leave
// its emission out (the sample counts it instead), at pixels and at hits alike, so nothing is
// counted twice. Without it a small bright emitter is found only by the few rays that happen
// to hit it: the Cornell box's light.
// The L1 SH weight of a sample of radiance from `direction` drawn with inverse pdf `inversePdf`
// (solid angle), so that it resolves to its irradiance L cos / pdf at the normal (shared/sh.h:
// E(n) = w L (1/4 + cos/2)); tlRtShSampleWeight is the case pdf = cos / pi.
TL_FN float tlRtShWeightForPdf(float cosTheta, float inversePdf) {
  float c = clamp(cosTheta, 0.0f, 1.0f);
  return c * inversePdf / (0.25f + 0.5f * c);
}

// Per-instance data the real rays read at a hit (gl_InstanceCustomIndexEXT), std430.
struct RtInstance {
  vec4 albedo;         // rgb: resolved hit albedo (override > baked > the texture-average fallback)
  vec4 emission;       // rgb: emitted radiance (factor x texture average)
  vec4 albedoScale;    // rgb: albedo / the texture-average fallback (1 unless a database entry or
                       // override applies): re-colours pre-traced hits, which read the G-buffer
  uvec2 indexAddress;  // device address of the instance's RT (simplified) triangle list
  uvec2 vertexAddress; // device address of its first vertex (tl::scene::Vertex, kVertexFloats floats)
  uint material;       // index into the scene's material table (alpha MASK: rt/alpha.rahit)
  uint pad0;
  uint pad1;
  uint pad2;
};

struct RtPush {
  float tMin;            // real rays start here: covers the simplified RT mesh's deviation
  float tMax;            // ray length (m)
  float aoRadius;        // RTAO radius (m)
  uint pretrace;         // 0: every ray is real
  uint pretraceSteps;    // depth-buffer samples along a pre-traced ray
  float pretraceLength;  // screen-space length of a pre-traced ray, in pixels
  float thickness;       // assumed depth of a depth-buffer surface, fraction of its view distance
  uint maxAccumFrames;   // temporal accumulation: history weight saturates at this many frames
  uint historyValid;     // 0: the history images hold nothing usable (first frame, resize, reset)
  uint specularRoughness; // reflections: half2 thresholds, traced below x, mirror below y (shared/rt_specular.h; 0: none)
  uint screenRadiance;   // hit lighting may reuse last frame's shaded pixels: kRtScreenRadiance*
  uint rayPattern;       // kRtRays*: which pixels trace this frame
  uint rawPendingOnly;   // benchmark probe: trace only the rays the pre-trace left pending
  float fireflyClamp;    // firefly suppression: ceiling in multiples of the neighbourhood / history luma (0: off)
  uint lightChanged;     // 1: the light changed since last frame: rectify the history (luminance rejection)
  uint disocclusionRays; // rays per low-resolution cell where history was rejected (0: none)
  uint hitSky;           // 1: hits lit afresh see the sky through one more ray
  uint emitterCount;     // emitter triangles sampled at pixels and hits (0: emission found by rays only)
  uint raysPerPixel;     // rays each traced pixel takes per frame: 1, or 2 (the trace and hit lighting run twice)
  uint sampleIndex;      // which of them this pass traces (0 or 1)
  vec4 cameraWorld;      // xyz: the camera's world position (emitters are stored in world space)
  // The radiance cache (shared/rt_cache.h):
  uint cacheLookup;      // 1: hits lit afresh take their incoming light from rt.cache.entries where a cell has it
  uint cacheEntryMask;   // its entries - 1
  float cacheCellSize;   // smallest cell (m)
  float cacheCellAngle;  // a cell is at least this many times its distance from the camera
  uint cacheBounces;     // rays of an update path
  uint cacheTile;        // one update path per cacheTile x cacheTile pixels
  float hitDistanceCap;  // a GI ray's hit distance counts as at most this, a miss as this (the denoiser's base radius, m)
  uint environmentSampling;  // 1: pixels sample the environment map by its importance (MIS with the GI ray; table bound)
};

// The two-pass spatial denoiser on the SH (Metro's "little monster"): its own push constants.
struct RtDenoisePush {
  float baseRadius;      // world radius before the variance and AO factors (m)
  uint normalWeight;     // 0: pass 1 (geometry only), 1: pass 2 (linear normal weight)
  float rotation;        // this frame's rotation of the Poisson disk (radians), the same for every pixel
  float planeDistance;   // a sample counts when within this fraction of the view distance of the tangent plane
  float hitDistanceCap;  // RtPush::hitDistanceCap: the hit distance at and beyond which the radius is not shrunk
  uint pad0, pad1, pad2;
};

// Bindings (set 0) of the RT path's passes; set 1 is the scene (shared/scene.h) where used.
// Slots every pass that includes rt/rt_common.glsl or rt/hit_lighting.glsl shares (the ray
// pipelines' stages must agree on them), then each shader's own, named by their role in it: a
// slot number may mean another thing in another shader.
TL_CONST uint kRtBindingFrame = 0;       // FrameConstants
TL_CONST uint kRtBindingTlas = 1;
TL_CONST uint kRtBindingBlueNoise = 2;   // rg16 unorm, 64 x 64
TL_CONST uint kRtBindingDepth = 3;       // gbuffer.depth
TL_CONST uint kRtBindingNormal = 4;      // gbuffer.normal
TL_CONST uint kRtBindingBaseColor = 5;   // gbuffer.baseColor
TL_CONST uint kRtBindingMaterial = 6;    // gbuffer.material
TL_CONST uint kRtBindingEmissive = 7;    // gbuffer.emissive
TL_CONST uint kRtBindingHitsIn = 8;      // r32ui hit records read (pre-trace result, or hits)
TL_CONST uint kRtBindingSurfaceIn = 9;   // rg32ui hit surface read
TL_CONST uint kRtBindingHitsOut = 10;    // r32ui hit records written
TL_CONST uint kRtBindingSurfaceOut = 11; // rg32ui hit surface written: x oct normal, y rgb9e5 emission
TL_CONST uint kRtBindingInstances = 12;  // RtInstance[]
TL_CONST uint kRtBindingPreviousViewDepth = 19;  // r32f: last frame's view depth (reprojection, screen radiance)
TL_CONST uint kRtBindingPreviousRadiance = 23;   // last frame's composite radiance (screen radiance at hits)
TL_CONST uint kRtBindingInstanceId = 26;     // gbuffer.instanceId (instance + 1, 0 = none)
TL_CONST uint kRtBindingEmitters = 32;       // Emitter[] (shared/emitters.h; at least one entry, RtPush::emitterCount of them valid)
TL_CONST uint kRtBindingCacheEntries = 37;   // RtCacheEntry[]: the radiance cache as hits read it (shared/rt_cache.h)
TL_CONST uint kRtBindingCacheAccum = 38;     // RtCacheAccum[]: its keys and this frame's sums
TL_CONST uint kRtBindingCacheSamples = 39;   // RtCacheSample[]: the update paths' samples
TL_CONST uint kRtBindingCacheOutcomes = 40;  // RtCacheOutcome[]: each update path's first ray and the light the cache adds there

// rt/lighting.rgen: a ray's hit lighting, written as raw SH; with two rays per pixel the
// second pass reads the first's and writes the mean.
TL_CONST uint kRtLightingOutShY = 13;    // rgba16f: L1 SH of luma
TL_CONST uint kRtLightingOutCoCg = 14;   // rg16f: chroma
TL_CONST uint kRtLightingOutAo = 15;     // rg16f: AO, hit distance (capped)
TL_CONST uint kRtLightingFirstShY = 33;  // the first ray's raw SH
TL_CONST uint kRtLightingFirstCoCg = 34;
TL_CONST uint kRtLightingFirstAo = 35;
// rt/raw.rgen: the benchmark's trivial kernel.
TL_CONST uint kRtRawDistances = 15;      // r32f: each ray's hit distance
// rt/temporal.comp: this frame's raw SH accumulated onto the reprojected history.
TL_CONST uint kRtTemporalRawShY = 13;
TL_CONST uint kRtTemporalRawCoCg = 14;
TL_CONST uint kRtTemporalRawAo = 15;
TL_CONST uint kRtTemporalMotion = 16;           // gbuffer.motion
TL_CONST uint kRtTemporalHistoryShY = 17;
TL_CONST uint kRtTemporalHistoryCoCgAo = 18;
TL_CONST uint kRtTemporalHistoryViewDepth = 19;
TL_CONST uint kRtTemporalHistoryMoment = 27;    // rg32f: the history's mean squared sample luma (firefly scale), mean inverse hit distance
TL_CONST uint kRtTemporalOutShY = 20;
TL_CONST uint kRtTemporalOutCoCgAo = 21;
TL_CONST uint kRtTemporalOutViewDepth = 22;
TL_CONST uint kRtTemporalOutMoment = 28;
// rt/ao_filter.comp: the accumulated AO filtered across pixels of similar depth.
TL_CONST uint kRtAoFilterAccumulated = 14;  // chroma (xy), AO (z)
TL_CONST uint kRtAoFilterViewDepth = 19;    // this frame's view depth
TL_CONST uint kRtAoFilterOut = 15;          // r16f
// rt/denoise.comp: one pass of the spatial denoiser (it also reads depth, normal, base colour, material).
TL_CONST uint kRtDenoiseInShY = 13;
TL_CONST uint kRtDenoiseInCoCgAo = 14;
TL_CONST uint kRtDenoiseLumaMoment = 36;    // the accumulation's mean squared sample luma (its noise estimate)
TL_CONST uint kRtDenoiseOutShY = 24;
TL_CONST uint kRtDenoiseOutCoCgAo = 25;
// rt/disocclusion.rgen: rays for the cells holding a pixel whose history was rejected, one texel per cell.
TL_CONST uint kRtDisocclusionAccumulated = 14;  // rt.gi.temporal.coCgAo: w = frames
TL_CONST uint kRtDisocclusionCellShY = 29;      // SH luma
TL_CONST uint kRtDisocclusionCellCoCgAo = 30;   // chroma (xy), AO (z)
TL_CONST uint kRtDisocclusionCellOrigin = 31;   // rgba32f: world position the rays left from (xyz), 1 if traced (w)
// rt/disocclusion_blend.comp: those cells' rays blended into the fresh pixels of the accumulation.
TL_CONST uint kRtBlendAccumulatedShY = 13;
TL_CONST uint kRtBlendAccumulatedCoCgAo = 14;
TL_CONST uint kRtBlendCellShY = 29;
TL_CONST uint kRtBlendCellCoCgAo = 30;
TL_CONST uint kRtBlendCellOrigin = 31;
TL_CONST uint kRtBlendOutShY = 20;
TL_CONST uint kRtBlendOutCoCgAo = 21;
// RtPush::screenRadiance: last frame's image is reused at hits seen on screen (Used); not this
// frame (Unavailable: a first frame, a restart, the light changed); or never (Off: the setting
// is off, every hit is lit afresh, and the radiance cache's vote counts every hit as off screen).
TL_CONST uint kRtScreenRadianceUnavailable = 0u;
TL_CONST uint kRtScreenRadianceUsed = 1u;
TL_CONST uint kRtScreenRadianceOff = 2u;
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::RtInstance) == 80);
static_assert(sizeof(tl::shared::RtPush) == 128);  // the least maxPushConstantsSize a device may have
static_assert(sizeof(tl::shared::RtDenoisePush) == 32);
#endif
#endif
