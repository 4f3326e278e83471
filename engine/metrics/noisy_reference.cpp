#include "metrics/noisy_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace tl::metrics {
namespace {

constexpr double kZ95 = 1.959963984540054;  // the normal's two-sided 95% point

// The reference's variance of value i (0 without one).
double varianceAt(const Image& variance, size_t i) {
  if (variance.data.empty()) return 0.0;
  const double v = variance.data[i];
  return std::isfinite(v) && v > 0.0 ? v : 0.0;
}

void requireVariance(const Image& reference, const Image& variance) {
  if (!variance.data.empty()) requireSameSize(reference, variance);
}

// g(r) = (t - r)^2 / (r^2 + eps) and its first, second and fourth derivatives in r: g = N W with
// N = (r - t)^2 (its third derivative 0) and W = 1 / s, s = r^2 + eps.
struct RelMseTerm {
  double g, g1, g2, g4;
};
RelMseTerm relMseTerm(double t, double r, double epsilon) {
  const double w = 1.0 / (r * r + epsilon), d = r - t, r2 = r * r;
  const double w1 = -2.0 * r * w * w;
  const double w2 = -2.0 * w * w + 8.0 * r2 * w * w * w;
  const double w3 = 24.0 * r * w * w * w - 48.0 * r2 * r * w * w * w * w;
  const double w4 = 24.0 * w * w * w - 288.0 * r2 * w * w * w * w + 384.0 * r2 * r2 * w * w * w * w * w;
  return {d * d * w, 2.0 * d * w + d * d * w1, 2.0 * w + 4.0 * d * w1 + d * d * w2, d * d * w4 + 8.0 * d * w3 + 12.0 * w2};
}

}  // namespace

NoiseAwareFigure relMseNoiseAware(const Image& test, const Image& reference, const Image& variance, double scale,
                                  double epsilon) {
  requireSameSize(test, reference);
  requireVariance(reference, variance);
  NoiseAwareFigure f;
  const size_t n = test.data.size();
  if (n == 0) return f;
  double raw = 0.0, debiased = 0.0, spread = 0.0, truncation = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double t = double(test.data[i]) * scale, r = double(reference.data[i]) * scale;
    if (!std::isfinite(t)) {  // a NaN in a path must show, as in relMse
      raw = debiased = std::numeric_limits<double>::infinity();
      break;
    }
    const double v = varianceAt(variance, i) * scale * scale;
    const RelMseTerm g = relMseTerm(t, r, epsilon);
    raw += g.g;
    // The unbiased estimator of g(r) from r̂ ~ N(r, v) is the heat equation run backwards,
    // g - v/2 g'' + v^2/8 g'''' - ..., here to the second order in v. The series is
    // asymptotic: where the noise is large against r^2 + eps its terms stop shrinking, so the
    // last term kept also widens the interval (the estimate's truncation error, roughly).
    const double first = 0.5 * v * g.g2, second = 0.125 * v * v * g.g4;
    debiased += g.g - first + second;
    // The next term, taken to shrink by the ratio of the last two (or to grow: then it counts more).
    truncation += std::abs(first) > 0.0 ? second * second / std::abs(first) : std::abs(second);
    // The spread (delta method): (t - r̂)^2 has variance 4 (t - r)^2 v + 2 v^2 for a normal r̂,
    // (t - r)^2 estimated without the noise; the weight 1 / (r̂^2 + eps) varies slowly beside it.
    const double w = 1.0 / (r * r + epsilon), truth2 = std::max((t - r) * (t - r) - v, 0.0);
    spread += w * w * (4.0 * truth2 * v + 2.0 * v * v);
  }
  f.raw = raw / double(n);
  f.value = debiased / double(n);
  const double half = (kZ95 * std::sqrt(spread) + truncation) / double(n);
  f.low = f.value - half;
  f.high = f.value + half;
  return f;
}

double expectedRelMse(const Image& reference, const Image& variance, double scale, double epsilon) {
  requireVariance(reference, variance);
  if (variance.data.empty() || reference.data.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < reference.data.size(); ++i) {
    const double r = double(reference.data[i]) * scale;
    sum += varianceAt(variance, i) * scale * scale / (r * r + epsilon);
  }
  return sum / double(reference.data.size());
}

NoiseAwareFigure simexNoiseAware(const Image& reference, const Image& variance,
                                 const std::function<double(const Image&)>& figure, int draws, uint64_t seed) {
  requireVariance(reference, variance);
  NoiseAwareFigure f;
  f.raw = figure(reference);
  bool noisy = false;
  for (size_t i = 0; i < variance.data.size() && !noisy; ++i) noisy = varianceAt(variance, i) > 0.0;
  if (!noisy || draws < 1 || !std::isfinite(f.raw)) {
    f.value = f.low = f.high = f.raw;
    return f;
  }
  // The figure at noise 2v and 3v (fresh normal noise of variance v and 2v added), `draws` times
  // each; the quadratic through (1, F1), (2, F2), (3, F3) in the noise's multiple, at 0.
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  double mean[2] = {0.0, 0.0}, squares[2] = {0.0, 0.0};
  Image noisier = reference;
  for (int level = 0; level < 2; ++level)
    for (int k = 0; k < draws; ++k) {
      const double extra = double(level + 1);
      for (size_t i = 0; i < noisier.data.size(); ++i)
        noisier.data[i] = float(double(reference.data[i]) + std::sqrt(extra * varianceAt(variance, i)) * normal(rng));
      const double value = figure(noisier);
      mean[level] += value / draws, squares[level] += value * value;
    }
  f.value = 3.0 * f.raw - 3.0 * mean[0] + mean[1];
  // The draws' spread at 2v stands for what the reference's own noise does to the figure: the
  // estimate 3 F1 - 3 F2 + F3 has about 9 + 9/draws + 1/draws times its variance (F1's
  // counted like the draws'), conservatively.
  const double s2 = draws > 1 ? std::max(squares[0] - draws * mean[0] * mean[0], 0.0) / (draws - 1) : 0.0;
  const double half = kZ95 * std::sqrt(s2 * (9.0 + 10.0 / draws));
  f.low = f.value - half;
  f.high = f.value + half;
  return f;
}

Ranking rank(const NoiseAwareFigure& a, const NoiseAwareFigure& b) {
  if (a.high < b.low) return Ranking::Lower;
  if (b.high < a.low) return Ranking::Higher;
  return Ranking::WithinNoise;
}

Threshold againstThreshold(const NoiseAwareFigure& f, double threshold) {
  if (f.low > threshold) return Threshold::Above;
  if (f.high <= threshold) return Threshold::Below;
  return Threshold::WithinNoise;
}

}  // namespace tl::metrics
