// The reference's noise as the session reports it, and renders that stop by it. The reference
// path keeps each pixel's running moments (reference.stderr: the standard error of its
// estimate) and sums them over the image every frame (reference.noise, 32 bytes read back);
// from that sum comes the relative standard error of the mean image (shared/reference.h
// tlRefRelativeStdError):
//   RSE = sqrt(mean over pixels and channels of Var(estimate)) / mean over pixels and channels of the estimate,
// the relative RMS distance the image is expected to have from the converged one.
#pragma once

#include <cstdint>
#include <optional>

namespace tl::session {

struct ReferenceNoise {
  double relativeStdError = 0.0;  // RSE of the mean image (above)
  double meanVariance = 0.0;      // mean over pixels and channels of Var(estimate) (the RSE's numerator, squared)
  double meanValue = 0.0;         // mean over pixels and channels of the estimate
  uint32_t fewestSamples = 0, mostSamples = 0;  // per pixel (adaptive sampling gives pixels different counts)
  double meanSamples = 0.0;
  // The samples a pixel took on average, the figure a render's "spp" means.
  uint32_t samplesPerPixel() const { return uint32_t(meanSamples + 0.5); }
};

// What renderReferenceUntilNoise aims at.
struct NoiseTarget {
  double relativeStdError = 0.01;
  // The cap: the render stops once the pixels have this many samples on average, target reached or not.
  static constexpr uint32_t kDefaultMaxSamples = 8192;
  uint32_t maxSamples = kDefaultMaxSamples;
  uint32_t samplesPerFrame = 16;  // RenderSettings::referenceSamplesPerFrame while it renders
};

// What it reached.
struct ReferenceConvergence {
  std::optional<ReferenceNoise> noise;  // at the last frame (empty: not yet defined)
  uint32_t frames = 0;
  bool reached = false;  // the target was met (else the cap stopped it)
  double seconds = 0.0;  // wall time of the frames
};

}  // namespace tl::session
