// Names of the RT path's graph resources (what tests, the inspector and captures ask for)
// and the parameters it resolves from the settings and the scene's size.
#pragma once

#include "lighting/common/frame_inputs.h"
#include "shared/rt.h"

namespace tl::lighting {

inline constexpr const char* kPretraceHits = "rt.pretrace.hits";
inline constexpr const char* kPretraceSurface = "rt.pretrace.surface";
inline constexpr const char* kHits = "rt.hits";
inline constexpr const char* kHitSurface = "rt.hitSurface";
inline constexpr const char* kRawShY = "rt.gi.raw.shY";
inline constexpr const char* kRawCoCg = "rt.gi.raw.coCg";
inline constexpr const char* kRawAo = "rt.ao.raw";
// The GI's stages, each its own resource: raw (one ray), temporal (accumulated), pass1 and
// pass2 of the spatial denoiser (pass2 is what the composite resolves).
inline constexpr const char* kShY = "rt.gi.temporal.shY";
inline constexpr const char* kCoCgAo = "rt.gi.temporal.coCgAo";
inline constexpr const char* kLumaMoment = "rt.gi.temporal.lumaMoment";
// Disocclusion rays (RE ENGINE): per 8x8 cell where history was rejected, many rays' mean;
// the accumulation with those cells filled into its fresh pixels ("filled") then feeds the
// history, the AO filter and the denoiser.
inline constexpr const char* kCellShY = "rt.gi.disocclusion.shY";
inline constexpr const char* kCellCoCgAo = "rt.gi.disocclusion.coCgAo";
inline constexpr const char* kCellOrigin = "rt.gi.disocclusion.origin";
inline constexpr const char* kFilledShY = "rt.gi.filled.shY";
inline constexpr const char* kFilledCoCgAo = "rt.gi.filled.coCgAo";
inline constexpr const char* kViewDepth = "rt.viewDepth";
inline constexpr const char* kAo = "rt.ao";
inline constexpr const char* kDenoise1ShY = "rt.gi.pass1.shY";
inline constexpr const char* kDenoise1CoCgAo = "rt.gi.pass1.coCgAo";
inline constexpr const char* kDenoisedShY = "rt.gi.pass2.shY";
inline constexpr const char* kDenoisedCoCgAo = "rt.gi.pass2.coCgAo";
inline constexpr const char* kHistShY = "rt.history.shY";
inline constexpr const char* kHistCoCgAo = "rt.history.coCgAo";
inline constexpr const char* kHistDepth = "rt.history.viewDepth";
inline constexpr const char* kHistLumaMoment = "rt.history.lumaMoment";
inline constexpr const char* kHistRadiance = "rt.history.radiance";
// Ray-traced reflections (shared/rt_specular.h): this frame's specular ray per pixel (raw),
// its temporal accumulation by virtual motion and hit distance, the lobe-sized filter's
// output the composite reads, and the two histories.
inline constexpr const char* kSpecularRaw = "rt.specular.raw";
inline constexpr const char* kSpecularTemporal = "rt.specular.temporal";
inline constexpr const char* kSpecularHitDistance = "rt.specular.hitDistance";
inline constexpr const char* kSpecular = "rt.specular";
inline constexpr const char* kHistSpecular = "rt.history.specular";
inline constexpr const char* kHistSpecularHit = "rt.history.specularHitDistance";
inline constexpr const char* kRawRays = "rt.rawRays";  // benchmark only: distances of the trivial kernel
inline constexpr const char* kRawRaysPending = "rt.rawRays.pending";  // the same, on the pre-trace's pending rays only

// What one ray per traced pixel reads and writes: the first ray's resources, and with two rays
// per pixel (rtTwoRays) the second's, whose hit lighting writes the mean of both.
struct RtRayResources {
  const char* pretracePass;
  const char* tracePass;
  const char* lightingPass;
  const char* pretraceHits;
  const char* pretraceSurface;
  const char* hits;
  const char* hitSurface;
  const char* shY;
  const char* coCg;
  const char* ao;
};
inline constexpr RtRayResources kFirstRay{"rt.pretrace", "rt.trace", "rt.lighting", kPretraceHits, kPretraceSurface,
                                          kHits,         kHitSurface, kRawShY,      kRawCoCg,         kRawAo};
inline constexpr RtRayResources kSecondRay{"rt.pretrace.2",    "rt.trace.2",     "rt.lighting.2",
                                           "rt.pretrace.hits.2", "rt.pretrace.surface.2", "rt.hits.2",
                                           "rt.hitSurface.2",  "rt.gi.raw2.shY", "rt.gi.raw2.coCg",
                                           "rt.ao.raw2"};

// Which pixels trace a ray each frame (shared/rt.h kRtRays*) for these settings.
inline uint32_t rtRayPattern(const RenderSettings& s) {
  return s.rtHalfResolution ? shared::kRtRaysHalfResolution
         : s.rtHalfRays     ? shared::kRtRaysCheckerboard
                            : shared::kRtRaysFull;
}

struct RtResolvedParams {
  float aoRadius = 0.0f;       // m
  float rayLength = 0.0f;      // m
  float blendDistance = 0.0f;  // m
  float tMin = 0.0f;           // m
};

}  // namespace tl::lighting
