#include "metrics/flip.h"

#include "metrics/metrics.h"
#include "shared/color.h"
#include "shared/tonemap.h"

#include <OpenImageIO/parallel.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace tl::metrics {
namespace {

// ---- the papers' constants, in one place -------------------------------------------------
constexpr double kQc = 0.7, kQf = 0.5, kPc = 0.4, kPt = 0.95, kFeatureWidth = 0.082;
// Contrast sensitivity as sums of two Gaussians (a1, b1, a2, b2) per opponent channel.
struct Csf { double a1, b1, a2, b2; };
constexpr Csf kCsfA{1.0, 0.0047, 0.0, 1e-5}, kCsfRg{1.0, 0.0053, 0.0, 1e-5}, kCsfBy{34.1, 0.04, 13.5, 0.025};
// D65 white in XYZ.
constexpr double kXn = 0.950428545, kYn = 1.0, kZn = 1.088900371;
constexpr double kPi = 3.14159265358979323846;

struct Vec3 { double x, y, z; };

Vec3 linearRgbToXyz(Vec3 c) {
  return {0.4124 * c.x + 0.3576 * c.y + 0.1805 * c.z, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
          0.0193 * c.x + 0.1192 * c.y + 0.9505 * c.z};
}
Vec3 xyzToLinearRgb(Vec3 c) {
  return {3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z, -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
          0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z};
}
Vec3 xyzToYcxcz(Vec3 c) {
  return {116.0 * c.y / kYn - 16.0, 500.0 * (c.x / kXn - c.y / kYn), 200.0 * (c.y / kYn - c.z / kZn)};
}
Vec3 ycxczToXyz(Vec3 c) {
  double y = (c.x + 16.0) / 116.0 * kYn;
  return {(c.y / 500.0 + y / kYn) * kXn, y, (y / kYn - c.z / 200.0) * kZn};
}
double labF(double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; }
// CIELab with the Hunt adjustment (chroma scaled by lightness / 100).
Vec3 huntLab(Vec3 rgb) {
  Vec3 x = linearRgbToXyz(rgb);
  double fx = labF(x.x / kXn), fy = labF(x.y / kYn), fz = labF(x.z / kZn);
  double l = 116.0 * fy - 16.0, a = 500.0 * (fx - fy), b = 200.0 * (fy - fz);
  return {l, 0.01 * l * a, 0.01 * l * b};
}
double hyab(Vec3 p, Vec3 q) { return std::abs(p.x - q.x) + std::hypot(p.y - q.y, p.z - q.z); }

// FLIP's filters are all separable, which turns each (2r+1)^2-tap 2D filter into two
// (2r+1)-tap passes (r = 10 for the CSF, 9 for the features at 67 pixels per degree):
//  - each contrast-sensitivity filter is a sum of one or two isotropic Gaussians, and a
//    Gaussian in d^2 = x^2 + y^2 is g(x) g(y);
//  - the edge and point detectors are the first and second derivative of a Gaussian along one
//    axis times the Gaussian along the other, and their normalisation (positive weights sum to
//    1, negative to -1) factors the same way.
// Borders clamp to the edge in x and in y independently, so the separable passes give the 2D
// filter's result; only the order of the double-precision sums differs (see docs/accuracy.md).
struct Kernel1D {
  int radius = 0;
  std::vector<double> w;  // taps -radius..radius
};

struct Plane {
  int w, h;
  std::vector<double> v;
};

// Runs rows [0, count) over OpenImageIO's thread pool; each row is written by one task, so the
// result does not depend on how the rows are split.
void forEachRow(int count, const std::function<void(int)>& row) {
  OIIO::parallel_for_range(int64_t(0), int64_t(count), [&](int64_t begin, int64_t end) {
    for (int64_t y = begin; y < end; ++y) row(int(y));
  });
}

// Correlation with kx along x, then ky along y, clamping coordinates at the borders.
Plane convolveSeparable(const Plane& in, const Kernel1D& kx, const Kernel1D& ky) {
  Plane mid{in.w, in.h, std::vector<double>(in.v.size())};
  forEachRow(in.h, [&](int y) {
    const double* src = &in.v[size_t(y) * in.w];
    double* dst = &mid.v[size_t(y) * in.w];
    for (int x = 0; x < in.w; ++x) {
      double s = 0.0;
      for (int i = -kx.radius; i <= kx.radius; ++i) s += kx.w[size_t(i + kx.radius)] * src[std::clamp(x + i, 0, in.w - 1)];
      dst[x] = s;
    }
  });
  Plane out{in.w, in.h, std::vector<double>(in.v.size())};
  forEachRow(in.h, [&](int y) {
    double* dst = &out.v[size_t(y) * in.w];
    for (int j = -ky.radius; j <= ky.radius; ++j) {
      const double k = ky.w[size_t(j + ky.radius)];
      const double* src = &mid.v[size_t(std::clamp(y + j, 0, in.h - 1)) * in.w];
      if (j == -ky.radius)
        for (int x = 0; x < in.w; ++x) dst[x] = k * src[x];
      else
        for (int x = 0; x < in.w; ++x) dst[x] += k * src[x];
    }
  });
  return out;
}

// One contrast-sensitivity filter: the normalised sum of its Gaussians as weighted separable
// terms. Term k is A_k e_k(x) e_k(y) with e_k(x) = exp(-pi^2 x^2 / (ppd^2 b_k)); with E_k the
// sum of e_k over the taps and S the sum of the whole 2D kernel (sum over k of A_k E_k^2),
// term k contributes A_k E_k^2 / S times the filter by (e_k / E_k) in x and in y.
struct CsfFilter {
  std::vector<std::pair<double, Kernel1D>> terms;  // weight, normalised 1D Gaussian
};

CsfFilter csfFilter(const Csf& c, double ppd, int radius) {
  CsfFilter f;
  double total = 0.0;
  for (auto [a, b] : {std::pair{c.a1, c.b1}, std::pair{c.a2, c.b2}}) {
    if (a == 0.0) continue;  // an absent second Gaussian
    Kernel1D k{radius, std::vector<double>(size_t(2 * radius + 1))};
    double sum = 0.0;
    for (int x = -radius; x <= radius; ++x) sum += k.w[size_t(x + radius)] = std::exp(-kPi * kPi * (double(x) * x) / (ppd * ppd * b));
    for (double& v : k.w) v /= sum;
    const double weight = a * std::sqrt(kPi / b) * sum * sum;
    total += weight;
    f.terms.push_back({weight, std::move(k)});
  }
  for (auto& t : f.terms) t.first /= total;
  return f;
}

Plane applyCsf(const Plane& in, const CsfFilter& f) {
  Plane out{in.w, in.h, std::vector<double>(in.v.size(), 0.0)};
  for (const auto& [weight, k] : f.terms) {
    const Plane term = convolveSeparable(in, k, k);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += weight * term.v[i];
  }
  return out;
}

// The feature detectors' 1D factors along the derivative's axis (edge: first derivative,
// point: second), each scaled so its positive taps sum to 1 and its negative ones to -1, and
// the normalised Gaussian across it.
struct FeatureKernels {
  Kernel1D gauss, edge, point;
};

FeatureKernels featureKernels(double ppd) {
  const double sigma = 0.5 * kFeatureWidth * ppd;
  const int radius = int(std::ceil(3.0 * sigma));
  FeatureKernels k;
  for (Kernel1D* kernel : {&k.gauss, &k.edge, &k.point}) *kernel = {radius, std::vector<double>(size_t(2 * radius + 1))};
  double gs = 0, ep = 0, en = 0, pp = 0, pn = 0;
  for (int x = -radius; x <= radius; ++x) {
    const size_t i = size_t(x + radius);
    const double g = std::exp(-(double(x) * x) / (2.0 * sigma * sigma));
    const double e = -x * g, p = (x * x / (sigma * sigma) - 1.0) * g;
    k.gauss.w[i] = g, k.edge.w[i] = e, k.point.w[i] = p;
    gs += g;
    (e > 0 ? ep : en) += e;
    (p > 0 ? pp : pn) += p;
  }
  for (double& g : k.gauss.w) g /= gs;
  for (double& e : k.edge.w) e /= e > 0 ? ep : -en;
  for (double& p : k.point.w) p /= p > 0 ? pp : -pn;
  return k;
}

// |response| of an achromatic plane to a detector along x and along y (the kernel transposed).
Plane featureMagnitude(const Plane& a, const Kernel1D& detector, const Kernel1D& gauss) {
  Plane gx = convolveSeparable(a, detector, gauss), gy = convolveSeparable(a, gauss, detector);
  for (size_t i = 0; i < gx.v.size(); ++i) gx.v[i] = std::hypot(gx.v[i], gy.v[i]);
  return gx;
}

struct Prepared {
  Plane channel[3];   // Y, Cx, Cz filtered
  Plane edges, points;
};

Prepared prepare(const Image& img, const CsfFilter* filters, const FeatureKernels& features) {
  const int w = int(img.width), h = int(img.height);
  Prepared p;
  Plane raw[3], achromatic{w, h, std::vector<double>(size_t(w) * h)};
  for (auto& c : raw) c = {w, h, std::vector<double>(size_t(w) * h)};
  forEachRow(h, [&](int y) {
    for (size_t i = size_t(y) * w; i < size_t(y + 1) * w; ++i) {
      const float* s = &img.data[i * img.channels];
      auto lin = [](float v) { return std::isfinite(v) ? double(shared::tlSrgbToLinear1(v)) : 0.0; };
      Vec3 ycc = xyzToYcxcz(linearRgbToXyz({lin(s[0]), lin(s[1]), lin(s[2])}));
      raw[0].v[i] = ycc.x, raw[1].v[i] = ycc.y, raw[2].v[i] = ycc.z;
      achromatic.v[i] = (ycc.x + 16.0) / 116.0;
    }
  });
  for (int c = 0; c < 3; ++c) p.channel[c] = applyCsf(raw[c], filters[c]);
  p.edges = featureMagnitude(achromatic, features.edge, features.gauss);
  p.points = featureMagnitude(achromatic, features.point, features.gauss);
  return p;
}

}  // namespace

MetricResult flipLdr(const Image& test, const Image& reference, double ppd) {
  requireSameSize(test, reference);
  if (test.channels < 3) throw std::invalid_argument("FLIP needs RGB images");
  double maxB = std::max({kCsfA.b1, kCsfA.b2, kCsfRg.b1, kCsfRg.b2, kCsfBy.b1, kCsfBy.b2});
  const int radius = int(std::ceil(3.0 * std::sqrt(maxB / (2.0 * kPi * kPi)) * ppd));
  const CsfFilter filters[3] = {csfFilter(kCsfA, ppd, radius), csfFilter(kCsfRg, ppd, radius), csfFilter(kCsfBy, ppd, radius)};
  const FeatureKernels features = featureKernels(ppd);
  const Prepared t = prepare(test, filters, features);
  const Prepared r = prepare(reference, filters, features);

  const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kQc);
  MetricResult out;
  out.errorMap = Image::filled(test.width, test.height, 1, 0.0f);
  std::vector<double> errors(test.pixels());
  forEachRow(int(test.height), [&](int y) {
    for (size_t i = size_t(y) * test.width; i < size_t(y + 1) * test.width; ++i) {
      auto rgbOf = [i](const Prepared& p) {
        Vec3 c = xyzToLinearRgb(ycxczToXyz({p.channel[0].v[i], p.channel[1].v[i], p.channel[2].v[i]}));
        return Vec3{std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0)};
      };
      double colour = std::pow(hyab(huntLab(rgbOf(t)), huntLab(rgbOf(r))), kQc);
      colour = colour < kPc * cmax ? kPt / (kPc * cmax) * colour
                                   : kPt + (colour - kPc * cmax) / (cmax - kPc * cmax) * (1.0 - kPt);
      colour = std::clamp(colour, 0.0, 1.0);
      double feature = std::pow(
          std::max(std::abs(r.edges.v[i] - t.edges.v[i]), std::abs(r.points.v[i] - t.points.v[i])) / std::sqrt(2.0), kQf);
      double e = std::pow(colour, 1.0 - std::clamp(feature, 0.0, 1.0));
      const float* s = &test.data[i * test.channels];
      if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || !std::isfinite(s[2])) e = 1.0;
      errors[i] = e;
      out.errorMap.data[i] = float(e);
    }
  });
  // The mean in pixel order, on one thread: the same sum every run.
  double sum = 0.0;
  for (double e : errors) sum += e;
  out.value = test.pixels() ? sum / double(test.pixels()) : 0.0;
  return out;
}

namespace {

// Inverse of the ACES tonemap's luminance response at `target` (bisection; monotonic).
double acesInverse(double target) {
  double lo = 0.0, hi = 1e4;
  for (int i = 0; i < 100; ++i) {
    double mid = 0.5 * (lo + hi);
    (shared::tlTonemapAces(glm::vec3(float(mid))).y < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Image exposed(const Image& linear, double exposure) {
  Image out = Image::filled(linear.width, linear.height, 3, 0.0f);
  for (size_t i = 0; i < linear.pixels(); ++i) {
    const float* s = &linear.data[i * linear.channels];
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || !std::isfinite(s[2])) {
      for (int c = 0; c < 3; ++c) out.data[i * 3 + c] = s[c];  // carried through: flipLdr scores it 1
      continue;
    }
    glm::vec3 d = shared::tlLinearToSrgb(shared::tlTonemapAces(glm::max(glm::vec3(s[0], s[1], s[2]), glm::vec3(0.0f)) *
                                                              float(exposure)));
    out.data[i * 3 + 0] = d.x, out.data[i * 3 + 1] = d.y, out.data[i * 3 + 2] = d.z;
  }
  return out;
}

}  // namespace

MetricResult flipHdr(const Image& test, const Image& reference, double ppd) {
  requireSameSize(test, reference);
  if (test.channels < 3) throw std::invalid_argument("HDR-FLIP needs RGB images");
  // Exposure range from the reference's luminance: from the one that maps its maximum to
  // 0.85 of the display range to the one that maps its median there (the HDR-FLIP paper
  // chooses its range from reference statistics in this spirit; the exact rule of the
  // paper is approximated here and documented in docs/accuracy.md).
  std::vector<double> lum;
  for (size_t i = 0; i < reference.pixels(); ++i) {
    const float* s = &reference.data[i * reference.channels];
    double y = 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2];
    if (std::isfinite(y) && y > 0.0) lum.push_back(y);
  }
  MetricResult out;
  out.errorMap = Image::filled(test.width, test.height, 1, 0.0f);
  if (lum.empty()) lum.push_back(1.0);
  std::sort(lum.begin(), lum.end());
  const double target = acesInverse(0.85);
  const double start = std::log2(target / lum.back()), stop = std::log2(target / lum[lum.size() / 2]);
  const int count = std::max(2, int(std::ceil(stop - start)) + 1);
  for (int k = 0; k < count; ++k) {
    double c = start + (stop - start) * k / double(count - 1);
    MetricResult m = flipLdr(exposed(test, std::exp2(c)), exposed(reference, std::exp2(c)), ppd);
    for (size_t i = 0; i < m.errorMap.data.size(); ++i)
      out.errorMap.data[i] = std::max(out.errorMap.data[i], m.errorMap.data[i]);
  }
  double sum = 0.0;
  for (float v : out.errorMap.data) sum += v;
  out.value = out.errorMap.data.empty() ? 0.0 : sum / double(out.errorMap.data.size());
  return out;
}

}  // namespace tl::metrics
