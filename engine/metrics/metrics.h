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

// Throws std::invalid_argument naming both sizes when they differ.
void requireSameSize(const Image& a, const Image& b);

}  // namespace tl::metrics
