#include "metrics/flip.h"

#include "metrics/metrics.h"
#include "shared/color.h"
#include "shared/tonemap.h"

#include <algorithm>
#include <cmath>
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

std::vector<double> csfKernel(const Csf& c, double ppd, int radius) {
  std::vector<double> k(size_t(2 * radius + 1) * (2 * radius + 1));
  double sum = 0.0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) {
      double d2 = (double(x) * x + double(y) * y) / (ppd * ppd);  // squared visual angle, degrees
      double g = c.a1 * std::sqrt(kPi / c.b1) * std::exp(-kPi * kPi * d2 / c.b1) +
                 c.a2 * std::sqrt(kPi / c.b2) * std::exp(-kPi * kPi * d2 / c.b2);
      k[size_t(y + radius) * (2 * radius + 1) + (x + radius)] = g;
      sum += g;
    }
  for (double& v : k) v /= sum;
  return k;
}

struct Plane {
  int w, h;
  std::vector<double> v;
  double at(int x, int y) const { return v[size_t(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)]; }
};

Plane convolve(const Plane& in, const std::vector<double>& k, int radius) {
  Plane out{in.w, in.h, std::vector<double>(in.v.size())};
  const int side = 2 * radius + 1;
  for (int y = 0; y < in.h; ++y)
    for (int x = 0; x < in.w; ++x) {
      double s = 0.0;
      for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i) s += k[size_t(j + radius) * side + (i + radius)] * in.at(x + i, y + j);
      out.v[size_t(y) * in.w + x] = s;
    }
  return out;
}

// Edge (first derivative of a Gaussian) and point (second derivative) kernels along x,
// each scaled so its positive weights sum to 1 and its negative weights to -1.
void featureKernels(double ppd, std::vector<double>& edge, std::vector<double>& point, int& radius) {
  const double sigma = 0.5 * kFeatureWidth * ppd;
  radius = int(std::ceil(3.0 * sigma));
  const int side = 2 * radius + 1;
  edge.assign(size_t(side) * side, 0.0);
  point.assign(size_t(side) * side, 0.0);
  double ep = 0, en = 0, pp = 0, pn = 0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) {
      double g = std::exp(-(double(x) * x + double(y) * y) / (2.0 * sigma * sigma));
      double e = -x * g, p = (x * x / (sigma * sigma) - 1.0) * g;
      size_t i = size_t(y + radius) * side + (x + radius);
      edge[i] = e, point[i] = p;
      (e > 0 ? ep : en) += e;
      (p > 0 ? pp : pn) += p;
    }
  for (double& e : edge) e /= e > 0 ? ep : -en;
  for (double& p : point) p /= p > 0 ? pp : -pn;
}

// |response| in x and y (the kernel transposed) of an achromatic plane.
Plane featureMagnitude(const Plane& a, const std::vector<double>& k, int radius) {
  const int side = 2 * radius + 1;
  std::vector<double> kt(k.size());
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) kt[size_t(y) * side + x] = k[size_t(x) * side + y];
  Plane gx = convolve(a, k, radius), gy = convolve(a, kt, radius);
  for (size_t i = 0; i < gx.v.size(); ++i) gx.v[i] = std::hypot(gx.v[i], gy.v[i]);
  return gx;
}

struct Prepared {
  Plane channel[3];   // Y, Cx, Cz filtered
  Plane achromatic;   // unfiltered Y / Yn, for features
};

Prepared prepare(const Image& img, const std::vector<double>* kernels, int radius, int featureRadius,
                 const std::vector<double>& edgeK, const std::vector<double>& pointK, Plane* edges, Plane* points) {
  const int w = int(img.width), h = int(img.height);
  Prepared p;
  for (auto& c : p.channel) c = {w, h, std::vector<double>(size_t(w) * h)};
  p.achromatic = {w, h, std::vector<double>(size_t(w) * h)};
  for (size_t i = 0; i < img.pixels(); ++i) {
    const float* s = &img.data[i * img.channels];
    auto lin = [](float v) { return std::isfinite(v) ? double(shared::tlSrgbToLinear1(v)) : 0.0; };
    Vec3 ycc = xyzToYcxcz(linearRgbToXyz({lin(s[0]), lin(s[1]), lin(s[2])}));
    p.channel[0].v[i] = ycc.x, p.channel[1].v[i] = ycc.y, p.channel[2].v[i] = ycc.z;
    p.achromatic.v[i] = (ycc.x + 16.0) / 116.0;
  }
  for (int c = 0; c < 3; ++c) p.channel[c] = convolve(p.channel[c], kernels[c], radius);
  *edges = featureMagnitude(p.achromatic, edgeK, featureRadius);
  *points = featureMagnitude(p.achromatic, pointK, featureRadius);
  return p;
}

}  // namespace

MetricResult flipLdr(const Image& test, const Image& reference, double ppd) {
  requireSameSize(test, reference);
  if (test.channels < 3) throw std::invalid_argument("FLIP needs RGB images");
  double maxB = std::max({kCsfA.b1, kCsfA.b2, kCsfRg.b1, kCsfRg.b2, kCsfBy.b1, kCsfBy.b2});
  const int radius = int(std::ceil(3.0 * std::sqrt(maxB / (2.0 * kPi * kPi)) * ppd));
  const std::vector<double> kernels[3] = {csfKernel(kCsfA, ppd, radius), csfKernel(kCsfRg, ppd, radius),
                                          csfKernel(kCsfBy, ppd, radius)};
  std::vector<double> edgeK, pointK;
  int fr = 0;
  featureKernels(ppd, edgeK, pointK, fr);
  Plane te, tp, re, rp;
  Prepared t = prepare(test, kernels, radius, fr, edgeK, pointK, &te, &tp);
  Prepared r = prepare(reference, kernels, radius, fr, edgeK, pointK, &re, &rp);

  const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kQc);
  MetricResult out;
  out.errorMap = Image::filled(test.width, test.height, 1, 0.0f);
  double sum = 0.0;
  for (size_t i = 0; i < test.pixels(); ++i) {
    auto rgbOf = [i](const Prepared& p) {
      Vec3 c = xyzToLinearRgb(ycxczToXyz({p.channel[0].v[i], p.channel[1].v[i], p.channel[2].v[i]}));
      return Vec3{std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0)};
    };
    double colour = std::pow(hyab(huntLab(rgbOf(t)), huntLab(rgbOf(r))), kQc);
    colour = colour < kPc * cmax ? kPt / (kPc * cmax) * colour
                                 : kPt + (colour - kPc * cmax) / (cmax - kPc * cmax) * (1.0 - kPt);
    colour = std::clamp(colour, 0.0, 1.0);
    double feature = std::pow(
        std::max(std::abs(re.v[i] - te.v[i]), std::abs(rp.v[i] - tp.v[i])) / std::sqrt(2.0), kQf);
    double e = std::pow(colour, 1.0 - std::clamp(feature, 0.0, 1.0));
    const float* s = &test.data[i * test.channels];
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || !std::isfinite(s[2])) e = 1.0;
    out.errorMap.data[i] = float(e);
    sum += e;
  }
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
