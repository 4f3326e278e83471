// The reference path tracer (engine/lighting/reference/): bindings, push constants,
// per-instance geometry and the payload its shaders exchange.
#ifndef TL_SHARED_REFERENCE_H
#define TL_SHARED_REFERENCE_H
#include "common.h"

TL_BEGIN
TL_CONST uint kRefBindingFrame = 0;      // FrameConstants (shared/frame.h)
TL_CONST uint kRefBindingTlas = 1;
TL_CONST uint kRefBindingPilotMean = 2;  // rgba32f: the pilot's sample mean (rgb), its samples (a) (persistent; below)
TL_CONST uint kRefBindingRadiance = 3;   // rgba32f: the estimate, sum / count
TL_CONST uint kRefBindingGeometry = 4;   // RefInstanceGeometry[]
TL_CONST uint kRefBindingVertices = 5;   // scene vertices as floats (kVertexFloats per vertex, shared/scene.h)
TL_CONST uint kRefBindingIndices = 6;    // scene indices
TL_CONST uint kRefBindingPilotMoments = 7;  // rgba32f: the pilot's squared deviations from its mean, summed (rgb) (persistent)
TL_CONST uint kRefBindingAo = 8;         // r32f: ambient occlusion at the AO radius, the mean of the pixel's samples
TL_CONST uint kRefBindingIrradianceAccum = 9;  // rgba32f: sum of irradiance samples (rgb) and their count (a)
TL_CONST uint kRefBindingIrradiance = 10;      // rgba32f: diffuse irradiance at the primary hit, sum / count
TL_CONST uint kRefBindingDepthAccum = 11;  // rgba32f: sums of the radiance by depth group (rgb) and their count (a)
TL_CONST uint kRefBindingDepth0 = 12;      // rgba32f: the radiance of depth group 0, sum / count; groups 1..3 at 13..15
TL_CONST uint kRefBindingMoments = 16;     // rgba32f: squared deviations from the pixel's sample mean, summed (rgb), samples (a) (persistent)
TL_CONST uint kRefBindingSampleMean = 17;  // rgba32f: the mean of the pixel's samples (rgb: the estimate; a: its AO) (persistent)
TL_CONST uint kRefBindingStdErr = 18;      // rgba32f: standard error of reference.radiance per channel (rgb), the pixel's samples (a)
TL_CONST uint kRefBindingEmitters = 19;    // Emitter[] (shared/emitters.h): RefPush::emitterCount of them (bound when > 0)
TL_CONST uint kRefBindingAllocation = 20;  // rgba32f: this frame's samples (x), the first one's number (y), the noise the next frame allocates by (z)
TL_CONST uint kRefBindingLastNoise = 21;   // RefNoiseTotals: the image's noise at the end of the last frame (persistent)
TL_CONST uint kRefBindingRawRays = 22;     // r32f: rays the benchmark's trivial kernel traced per pixel (reference/raw.rgen)
TL_CONST uint kRefBindingLobe0 = 23;       // rgba32f: the light the first surface reflects through its diffuse layer, sum / count; its specular lobes' at 24

// Adaptive sampling (RefPush::adaptive). Each frame's samples of a pixel are drawn in proportion
// to the standard deviation of its samples, sigma = sqrt(sum over channels of s_c^2), over the
// image's mean sigma (what minimises the image's summed variance, the RSE's numerator, for a
// fixed number of samples). The estimate stays the plain mean of the pixel's samples, which
// is unbiased only if the counts do not depend on the samples they average: the counts are
// decided by a pilot, a second, independent stream of samples of the same pixel (its own random
// numbers) that the estimate never averages. kRefAdaptiveOwn decides them by the estimate's own
// samples instead: biased (a pixel whose samples so far happen to agree gets fewer more), kept
// as the diagnostic that shows why the pilot exists.
TL_CONST uint kRefAdaptiveOff = 0;    // every pixel the same samples each frame
TL_CONST uint kRefAdaptivePilot = 1;  // by the pilot's sigma (unbiased)
TL_CONST uint kRefAdaptiveOwn = 2;    // by the estimate's own sigma (biased; diagnostic)
// The pilot's share of the samples: one pilot sample for every kRefPilotEvery the image draws
// (a pixel's sigma needs only rough precision: an allocation off by a factor (1 + e) costs a
// fraction of order e^2 of its gain), and one each frame until a pixel has kRefPilotWarmup.
TL_CONST uint kRefPilotEvery = 16u;
TL_CONST uint kRefPilotWarmup = 4u;
// A share of every frame's samples stays uniform, so a pixel whose pilot saw no variance yet
// (a rare path not drawn) still converges: its variance is at most 1 / kRefAdaptiveFloor times
// the uniform allocation's. A pixel takes at most kRefAdaptiveMost times the mean in a frame
// (a frame's cost stays bounded, and so does the imbalance between neighbouring invocations).
TL_CONST float kRefAdaptiveFloor = 0.125f;
TL_CONST float kRefAdaptiveMost = 16.0f;

// The reference's noise, summed over the image in two steps (reference/noise_tiles.comp: tiles of
// kRefNoiseTile x kRefNoiseTile pixels; reference/noise_sum.comp: the tiles) into one RefNoiseTotals.
TL_CONST uint kRefNoiseTile = 16u;
TL_CONST uint kRefNoiseBindingRadiance = 0;  // reference.radiance (tile step)
TL_CONST uint kRefNoiseBindingStdErr = 1;    // reference.stderr (tile step)
TL_CONST uint kRefNoiseBindingTiles = 2;     // RefNoiseTotals per tile: written by the tile step, read by the sum
TL_CONST uint kRefNoiseBindingTotals = 3;    // RefNoiseTotals: the whole image (sum step)
TL_CONST uint kRefNoiseBindingAllocation = 4;  // reference.allocation (tile step: the sigma adaptive sampling allocates by)

// The radiance by path depth (scattering events between light and camera), in four groups:
// 0-1 (emission and direct light), 2 (the first bounce), 3 (the second), 4 and more.
TL_CONST uint kRefDepthGroups = 4;
// The same radiance split by the lobe of the first surface the camera sees that reflected it:
// [0] its diffuse layer, [1] its specular lobes (the sun's highlight, reflections). What the
// camera sees directly (emission, the sky, the environment) is in neither, so the two sum to
// the radiance less that. Summed in the depth split's image, below its groups' rows.
TL_CONST uint kRefLobes = 2;


// Where an instance's triangles are in the scene's shared vertex/index buffers.
struct RefInstanceGeometry {
  uint firstIndex;
  int vertexOffset;
  uint material;
  uint emitters;  // its first entry in the emitter table + 1 (0: it emits nothing): triangle t is entry emitters - 1 + t
};

// What the noise passes add up, over pixels and the three channels.
struct RefNoiseTotals {
  vec4 sums;     // x: variance of each pixel's estimate (stderr^2), y: the estimates, z: samples, w: the sigma
                 // adaptive sampling allocates by (reference.allocation z)
  uvec4 counts;  // x: pixels, y: pixels with fewer than 2 samples (no variance yet), z: fewest samples, w: most
};

// The relative standard error of the reference's mean image: the root of the mean over pixels
// and channels of the variance of each pixel's estimate, over the mean of the estimates,
//   RSE = sqrt(sum_pc Var(r_pc) / 3P) / (sum_pc r_pc / 3P).
// It is how far (relative RMS) the image is expected to be from the converged one. Undefined
// (negative) until every pixel has 2 samples; 0 for an image with no light (every sample 0).
TL_FN float tlRefRelativeStdError(RefNoiseTotals t) {
  if (t.counts.x == 0u || t.counts.y > 0u) return -1.0f;
  if (!(t.sums.y > 0.0f)) return 0.0f;
  float n = 3.0f * float(t.counts.x);
  return sqrt(max(t.sums.x, 0.0f) / n) / (t.sums.y / n);
}

struct RefNoisePush {
  uint width, height;  // the image (tile step)
  uint tiles;          // tiles to sum (sum step)
  uint pad;
};

struct RefPush {
  uint samplesSoFar;     // accumulated before this frame (0: start over)
  uint samplesPerFrame;
  uint maxBounces;       // scattering events per path (1 = direct light only, 2 = plus one bounce)
  uint seed;
  float aoRadius;        // reference AO: one cosine ray per sample from the primary hit, this long (m)
  uint pad;
  uint emitterCount;     // emissive triangles sampled at every scattering event (0: emission found by rays only)
  uint adaptive;         // kRefAdaptiveOff, kRefAdaptivePilot or kRefAdaptiveOwn (the trace pass; 0 elsewhere)
};

// What a closest-hit shader reports (hitT < 0: the ray missed).
struct RefHit {
  vec4 positionT;     // xyz camera-relative hit point, w hit distance
  vec4 normal;        // xyz shading normal facing the ray; w 1 where the ray met a single-sided surface from
                      // behind (camera rays pass it: glTF doubleSided, shared/scene.h), else 0
  vec4 geometric;     // xyz geometric normal facing the ray; w the density per unit area with which emitter
                      // sampling draws the hit point (its triangle's probability / area; 0: never)
  vec4 baseColor;     // rgb, a roughness
  vec4 emission;      // rgb emitted radiance, a metallic
  vec4 fresnel;       // the dielectric's F0 (rgb) and F90 (a): KHR_materials_ior / specular (shared/scene.h)
  vec4 transmission;  // x KHR_materials_transmission (factor x texture, 0: opaque); y 1 where the mesh bounds a
                      // volume (KHR_materials_volume); z 1 where the ray met the surface's back; w the ior
  vec4 absorption;    // rgb the volume's absorption per scene unit (KHR_materials_volume), 0 for a thin surface
  vec4 coat;          // x KHR_materials_clearcoat's factor, y its roughness
};

// The hit groups: paths' rays (trace.rchit, alpha.rahit) and shadow rays (shadow.rahit), the
// traceRayEXT sbtRecordOffset each takes.
TL_CONST uint kRefPathHitGroup = 0;
TL_CONST uint kRefShadowHitGroup = 1;

// A shadow ray's payload (location 1): what the thin transmitting surfaces it crossed let
// through (their transmittance multiplied), and whether it reached its end (the miss shader sets
// `reached`; an opaque hit ends it without).
struct RefShadowRay {
  vec3 transmittance;
  float reached;
};
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::RefInstanceGeometry) == 16);
static_assert(sizeof(tl::shared::RefPush) == 32);
static_assert(sizeof(tl::shared::RefNoiseTotals) == 32);
static_assert(sizeof(tl::shared::RefNoisePush) == 16);
#endif
#endif
