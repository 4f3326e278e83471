// Names of the RT path's graph resources (what tests, the inspector and captures ask for)
// and the parameters it resolves from the settings and the scene's size.
#pragma once

#include "lighting/common/frame_inputs.h"
#include "shared/rt.h"

namespace tl::lighting {

inline constexpr graph::ImageName kPretraceHits{"rt.pretrace.hits"};
inline constexpr graph::ImageName kPretraceSurface{"rt.pretrace.surface"};
inline constexpr graph::ImageName kHits{"rt.hits"};
inline constexpr graph::ImageName kHitSurface{"rt.hitSurface"};
inline constexpr graph::ImageName kRawShY{"rt.gi.raw.shY"};
inline constexpr graph::ImageName kRawCoCg{"rt.gi.raw.coCg"};
inline constexpr graph::ImageName kRawAo{"rt.ao.raw"};
// The GI's stages, each its own resource: raw (one ray), temporal (accumulated), pass1 and
// pass2 of the spatial denoiser (pass2 is what the composite resolves).
inline constexpr graph::ImageName kShY{"rt.gi.temporal.shY"};
inline constexpr graph::ImageName kCoCgAo{"rt.gi.temporal.coCgAo"};
inline constexpr graph::ImageName kLumaMoment{"rt.gi.temporal.lumaMoment"};
// Disocclusion rays (RE ENGINE): per 8x8 cell where history was rejected, many rays' mean;
// the accumulation with those cells filled into its fresh pixels ("filled") then feeds the
// history, the AO filter and the denoiser.
inline constexpr graph::ImageName kCellShY{"rt.gi.disocclusion.shY"};
inline constexpr graph::ImageName kCellCoCgAo{"rt.gi.disocclusion.coCgAo"};
inline constexpr graph::ImageName kCellOrigin{"rt.gi.disocclusion.origin"};
inline constexpr graph::ImageName kFilledShY{"rt.gi.filled.shY"};
inline constexpr graph::ImageName kFilledCoCgAo{"rt.gi.filled.coCgAo"};
inline constexpr graph::ImageName kViewDepth{"rt.viewDepth"};
inline constexpr graph::ImageName kAo{"rt.ao"};
inline constexpr graph::ImageName kDenoise1ShY{"rt.gi.pass1.shY"};
inline constexpr graph::ImageName kDenoise1CoCgAo{"rt.gi.pass1.coCgAo"};
inline constexpr graph::ImageName kDenoisedShY{"rt.gi.pass2.shY"};
inline constexpr graph::ImageName kDenoisedCoCgAo{"rt.gi.pass2.coCgAo"};
inline constexpr graph::ImageName kHistShY{"rt.history.shY"};
inline constexpr graph::ImageName kHistCoCgAo{"rt.history.coCgAo"};
inline constexpr graph::ImageName kHistDepth{"rt.history.viewDepth"};
inline constexpr graph::ImageName kHistLumaMoment{"rt.history.lumaMoment"};
inline constexpr graph::ImageName kHistRadiance{"rt.history.radiance"};
// Ray-traced reflections (shared/rt_specular.h): this frame's specular ray per pixel (raw),
// its temporal accumulation by virtual motion and hit distance, the lobe-sized filter's
// output the composite reads, and the two histories.
inline constexpr graph::ImageName kSpecularRaw{"rt.specular.raw"};
inline constexpr graph::ImageName kSpecularTemporal{"rt.specular.temporal"};
inline constexpr graph::ImageName kSpecularHitDistance{"rt.specular.hitDistance"};
inline constexpr graph::ImageName kSpecular{"rt.specular"};
inline constexpr graph::ImageName kHistSpecular{"rt.history.specular"};
inline constexpr graph::ImageName kHistSpecularHit{"rt.history.specularHitDistance"};
inline constexpr graph::ImageName kRawRays{"rt.rawRays"};  // benchmark only: distances of the trivial kernel
inline constexpr graph::ImageName kRawRaysPending{"rt.rawRays.pending"};  // the same, on the pre-trace's pending rays only

// What one ray per traced pixel reads and writes: the first ray's resources, and with two rays
// per pixel (rtTwoRays) the second's, whose hit lighting writes the mean of both.
struct RtRayResources {
  const char* pretracePass;
  const char* tracePass;
  const char* lightingPass;
  graph::ImageName pretraceHits;
  graph::ImageName pretraceSurface;
  graph::ImageName hits;
  graph::ImageName hitSurface;
  graph::ImageName shY;
  graph::ImageName coCg;
  graph::ImageName ao;
};
inline constexpr RtRayResources kFirstRay{"rt.pretrace", "rt.trace", "rt.lighting", kPretraceHits, kPretraceSurface,
                                          kHits,         kHitSurface, kRawShY,      kRawCoCg,         kRawAo};
inline constexpr RtRayResources kSecondRay{"rt.pretrace.2",
                                           "rt.trace.2",
                                           "rt.lighting.2",
                                           graph::ImageName{"rt.pretrace.hits.2"},
                                           graph::ImageName{"rt.pretrace.surface.2"},
                                           graph::ImageName{"rt.hits.2"},
                                           graph::ImageName{"rt.hitSurface.2"},
                                           graph::ImageName{"rt.gi.raw2.shY"},
                                           graph::ImageName{"rt.gi.raw2.coCg"},
                                           graph::ImageName{"rt.ao.raw2"}};

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
