// Error figures against a reference that is itself noisy: a path tracer's image is the mean of
// n samples, r̂ = r + e with E[e] = 0 and Var(e) = v per pixel and channel (the reference's
// reference.stderr squared). An error measured against r̂ carries r̂'s noise besides the error
// against the converged r:
//   E[(t - r̂)^2] = (t - r)^2 + v,
// so at low sample counts every figure is biased upwards by the reference's noise and rankings
// flip. These functions take v out of the expectation and give each figure a 95% confidence
// interval from the reference's noise; comparisons rank two figures only when their intervals
// do not overlap, and say "within noise" otherwise (docs/accuracy.md, "Significance").
#pragma once

#include "metrics/image.h"
#include "metrics/metrics.h"

#include <cstdint>
#include <functional>
#include <string>

namespace tl::metrics {

// A figure against the converged reference, estimated from a noisy one.
struct NoiseAwareFigure {
  double value = 0.0;  // the estimate (the noise taken out: may fall a little below 0 where t = r)
  double raw = 0.0;    // the figure against the noisy reference, as measured
  double low = 0.0, high = 0.0;  // its 95% confidence interval from the reference's noise
};

// relMSE = mean over pixels and channels of g(r) = (t - r)^2 / (r^2 + epsilon). Its numerator
// alone would be debiased by subtracting v: E[(t - r̂)^2] = (t - r)^2 + v. The denominator is
// noisy too, so the estimate is the unbiased estimator of g(r) from r̂ ~ N(r, v) (the heat
// equation run backwards) to the second order in v:
//   value = mean of g(r̂) - v/2 g''(r̂) + v^2/8 g''''(r̂),
// whose leading correction is the subtraction above, v / (r̂^2 + eps). The interval is the delta
// method with each pixel's r̂ normal (a mean of many samples) and the pixels independent:
// Var((t - r̂)^2) = 4 (t - r)^2 v + 2 v^2, (t - r)^2 estimated by max((t - r̂)^2 - v, 0):
//   value +- (1.96 sqrt(sum of w^2 (4 d^2 v + 2 v^2)) + truncation) / N,  w = 1 / (r̂^2 + eps),
// the truncation the series' next term, guessed from the ratio of its last two (where the noise
// is large against r^2 + eps the series stops converging and the interval widens with it).
// `variance` has the reference's channels (3) or is empty (a noiseless reference: value = raw,
// a zero-width interval). Both images are scaled by `scale` first (exposure normalisation: v by
// scale^2).
NoiseAwareFigure relMseNoiseAware(const Image& test, const Image& reference, const Image& variance, double scale = 1.0,
                                  double epsilon = kRelMseEpsilon);

// The reference's own expected relMSE against the image it converges to: mean of v / (r̂^2 + eps),
// both scaled by `scale` (relMSE_norm with the exposure normalisation's factor).
double expectedRelMse(const Image& reference, const Image& variance, double scale = 1.0, double epsilon = kRelMseEpsilon);

// A figure that is not a mean of per-pixel squares (FLIP), by simulation-extrapolation (SIMEX,
// Cook & Stefanski 1994): F1 = figure(r̂) at the reference's noise v, F2 and F3 the means of
// figure(r̂ + e') over `draws` copies with fresh normal noise e' of variance v and 2v (noise 2v
// and 3v); the quadratic through the three in the noise's multiple, taken to no noise, is
// 3 F1 - 3 F2 + F3. The interval: the spread s of the draws at 2v is what noise v does to the
// figure; value +- 1.96 s sqrt(9 + 10/draws). Deterministic (`seed`).
NoiseAwareFigure simexNoiseAware(const Image& reference, const Image& variance,
                                 const std::function<double(const Image& reference)>& figure, int draws = 3,
                                 uint64_t seed = 1);

// How two figures (larger is worse) compare: one is lower only when its interval lies wholly
// below the other's.
enum class Ranking { Lower, Higher, WithinNoise };
Ranking rank(const NoiseAwareFigure& a, const NoiseAwareFigure& b);
// A figure against a threshold: above it only when its whole interval is, within it only when
// its whole interval is; else within noise of it.
enum class Threshold { Below, Above, WithinNoise };
Threshold againstThreshold(const NoiseAwareFigure& f, double threshold);

}  // namespace tl::metrics
