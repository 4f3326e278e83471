// Error metrics against a reference image, each with a per-pixel error map. Inputs are
// linear radiance unless stated; docs/accuracy.md gives the definitions.
#pragma once

#include "metrics/image.h"

namespace tl::metrics {

// Relative MSE: mean over pixels and channels of (t - r)^2 / (r^2 + epsilon). The fixed
// epsilon keeps black reference pixels from dominating.
inline constexpr double kRelMseEpsilon = 1e-2;
MetricResult relMse(const Image& test, const Image& reference, double epsilon = kRelMseEpsilon);
MetricResult rmse(const Image& test, const Image& reference);
// 20 log10(peak / RMSE); +infinity for identical images.
double psnr(const Image& test, const Image& reference, double peak);
// SSIM (Wang et al. 2004) of luminance (Rec. 709 weights of the first three channels, or
// the one channel): 11x11 Gaussian window, sigma 1.5, K1 = 0.01, K2 = 0.03; the window is
// clamped at the borders. Display-encoded inputs in [0, dynamicRange].
MetricResult ssim(const Image& test, const Image& reference, double dynamicRange = 1.0);

// Temporal flicker between two consecutive frames of a moving camera: the mean over pixels of
// |Y(current) - Y(previous at the pixel's reprojected position)| divided by the mean Y of the
// current frame (Y: Rec. 709 luminance of the first three channels). `motion` holds the
// screen-space motion per pixel in UV units, two channels, as gbuffer.motion: the previous
// position is uv - motion, read with the nearest texel. Pixels that come from off screen are
// left out. 0 for a perfectly steady image; resampling alone gives a small floor.
double flicker(const Image& previous, const Image& current, const Image& motion);

// Exposure normalisation: both images scaled by one factor so the reference's mean luminance
// (Rec. 709 weights of the first three channels, non-finite pixels left out) becomes 0.18,
// so relMSE's fixed epsilon means the same in a dark scene as in a bright one. The factor is
// 1 for a reference with no light (nothing to normalise).
inline constexpr double kNormalisedMeanLuminance = 0.18;
double exposureNormalisation(const Image& reference);
// Mean luminance (Rec. 709 weights of the first three channels, or the one channel;
// non-finite pixels count as 0).
double meanLuminance(const Image& image);
Image scaled(const Image& image, double factor);
// relMSE of the two images after exposure normalisation: unchanged when both are scaled alike.
MetricResult relMseNormalised(const Image& test, const Image& reference, double epsilon = kRelMseEpsilon);

// Throws std::invalid_argument naming both sizes when they differ.
void requireSameSize(const Image& a, const Image& b);

}  // namespace tl::metrics
