// FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images") and
// HDR-FLIP (Andersson et al. 2021, "Visualizing Errors in Rendered High Dynamic Range
// Images"): per-pixel perceived difference in [0, 1] and its mean.
#pragma once

#include "metrics/image.h"

namespace tl::metrics {

// Pixels per degree of visual angle: 67 is the papers' default (a 0.7 m viewing distance
// from a 24-inch 4K monitor).
inline constexpr double kDefaultPixelsPerDegree = 67.0;

// LDR-FLIP of display-encoded sRGB images with values in [0, 1] (RGB, 3 channels).
// Non-finite test pixels count as the maximal error 1.
MetricResult flipLdr(const Image& test, const Image& reference, double pixelsPerDegree = kDefaultPixelsPerDegree);

// HDR-FLIP of linear radiance images (RGB): LDR-FLIP of the two images tonemapped (ACES)
// at a range of exposures chosen from the reference, per-pixel maximum.
MetricResult flipHdr(const Image& test, const Image& reference, double pixelsPerDegree = kDefaultPixelsPerDegree);

}  // namespace tl::metrics
