#include "metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tl::metrics {

void requireSameSize(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + "x" +
                                std::to_string(a.channels) + " against " + std::to_string(b.width) + "x" +
                                std::to_string(b.height) + "x" + std::to_string(b.channels));
}

namespace {

// Mean over channels of f(t, r) per pixel, and the mean of that over the image. A
// non-finite test value makes its pixel (and so the mean) +infinity: a NaN in a lighting
// path must show up, not vanish.
template <class F>
MetricResult perPixel(const Image& t, const Image& r, F f) {
  requireSameSize(t, r);
  MetricResult out;
  out.errorMap = Image::filled(t.width, t.height, 1, 0.0f);
  double sum = 0.0;
  for (size_t i = 0; i < t.pixels(); ++i) {
    double e = 0.0;
    for (uint32_t c = 0; c < t.channels; ++c) {
      double tv = t.data[i * t.channels + c], rv = r.data[i * r.channels + c];
      e += std::isfinite(tv) ? f(tv, rv) : std::numeric_limits<double>::infinity();
    }
    e /= t.channels;
    out.errorMap.data[i] = float(e);
    sum += e;
  }
  out.value = t.pixels() ? sum / double(t.pixels()) : 0.0;
  return out;
}

std::vector<double> luminance(const Image& img) {
  std::vector<double> y(img.pixels());
  for (size_t i = 0; i < y.size(); ++i) {
    const float* p = &img.data[i * img.channels];
    y[i] = img.channels >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
    if (!std::isfinite(y[i])) y[i] = 0.0;
  }
  return y;
}

}  // namespace

MetricResult relMse(const Image& t, const Image& r, double epsilon) {
  return perPixel(t, r, [epsilon](double tv, double rv) { return (tv - rv) * (tv - rv) / (rv * rv + epsilon); });
}

double flicker(const Image& previous, const Image& current, const Image& motion) {
  requireSameSize(previous, current);
  if (motion.width != current.width || motion.height != current.height || motion.channels < 2)
    throw std::invalid_argument("flicker: the motion image must match the frames' size and have two channels");
  auto luma = [](const Image& im, uint32_t x, uint32_t y) {
    if (im.channels < 3) return double(im.at(x, y, 0));
    return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
  };
  double change = 0.0, level = 0.0;
  size_t n = 0;
  for (uint32_t y = 0; y < current.height; ++y)
    for (uint32_t x = 0; x < current.width; ++x) {
      const double u = (x + 0.5) / current.width - motion.at(x, y, 0);
      const double v = (y + 0.5) / current.height - motion.at(x, y, 1);
      if (!(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0)) continue;
      const uint32_t px = std::min(uint32_t(u * current.width), current.width - 1);
      const uint32_t py = std::min(uint32_t(v * current.height), current.height - 1);
      const double c = luma(current, x, y);
      change += std::abs(c - luma(previous, px, py));
      level += c;
      ++n;
    }
  return n > 0 && level > 0.0 ? change / level : 0.0;
}

double meanLuminance(const Image& image) {
  const std::vector<double> y = luminance(image);
  double sum = 0.0;
  for (double v : y) sum += v;  // luminance() zeroes non-finite pixels
  return y.empty() ? 0.0 : sum / double(y.size());
}

double exposureNormalisation(const Image& reference) {
  const double mean = meanLuminance(reference);
  return mean > 0.0 ? kNormalisedMeanLuminance / mean : 1.0;
}

Image scaled(const Image& image, double factor) {
  Image out = image;
  for (float& v : out.data) v = float(double(v) * factor);
  return out;
}

MetricResult relMseNormalised(const Image& t, const Image& r, double epsilon) {
  const double k = exposureNormalisation(r);
  return relMse(scaled(t, k), scaled(r, k), epsilon);
}

MetricResult rmse(const Image& t, const Image& r) {
  MetricResult m = perPixel(t, r, [](double tv, double rv) { return (tv - rv) * (tv - rv); });
  m.value = std::sqrt(m.value);
  for (auto& v : m.errorMap.data) v = std::sqrt(v);
  return m;
}

double psnr(const Image& t, const Image& r, double peak) {
  double e = rmse(t, r).value;
  if (e == 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(peak / e);
}

MetricResult ssim(const Image& t, const Image& r, double range) {
  requireSameSize(t, r);
  const int radius = 5;
  double weights[2 * radius + 1], total = 0.0;
  for (int i = -radius; i <= radius; ++i) total += weights[i + radius] = std::exp(-0.5 * i * i / (1.5 * 1.5));
  for (double& w : weights) w /= total;
  const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
  std::vector<double> x = luminance(t), y = luminance(r);
  const int w = int(t.width), h = int(t.height);
  // Separable Gaussian moments: mean, squares and cross product.
  auto blur = [&](const std::vector<double>& in) {
    std::vector<double> tmp(in.size()), out(in.size());
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        double s = 0.0;
        for (int k = -radius; k <= radius; ++k) s += weights[k + radius] * in[size_t(py) * w + std::clamp(px + k, 0, w - 1)];
        tmp[size_t(py) * w + px] = s;
      }
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        double s = 0.0;
        for (int k = -radius; k <= radius; ++k) s += weights[k + radius] * tmp[size_t(std::clamp(py + k, 0, h - 1)) * w + px];
        out[size_t(py) * w + px] = s;
      }
    return out;
  };
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (size_t i = 0; i < x.size(); ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  auto mx = blur(x), my = blur(y), sxx = blur(xx), syy = blur(yy), sxy = blur(xy);
  MetricResult out;
  out.errorMap = Image::filled(t.width, t.height, 1, 0.0f);
  double sum = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
    double s = ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
    out.errorMap.data[i] = float(s);
    sum += s;
  }
  out.value = x.empty() ? 1.0 : sum / double(x.size());
  return out;
}

}  // namespace tl::metrics
