// Fresnel's equations: the closed form that the dielectric surfaces and glass are held to
// (not the BRDF's Schlick approximation or its tables).
#pragma once

#include <algorithm>
#include <cmath>

namespace tl::test {

// The reflectance of unpolarised light from air into a dielectric of index n at cos theta = cosI.
inline double fresnelReflectance(double n, double cosI) {
  const double sinT = std::sqrt(std::max(0.0, 1.0 - cosI * cosI)) / n, cosT = std::sqrt(1.0 - sinT * sinT);
  const double s = (cosI - n * cosT) / (cosI + n * cosT), p = (cosT - n * cosI) / (cosT + n * cosI);
  return 0.5 * (s * s + p * p);
}

}  // namespace tl::test
