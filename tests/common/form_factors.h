// Closed-form form factors from a point to a parallel emitter (the irradiance under a
// Lambertian emitter of radiance L is E = pi L F): the truths the area-light tests measure
// every path against, written once for the unit and the GPU tests.
#pragma once

#include <cmath>

namespace tl::test {

// To a parallel disk of radius r at height h, the point a from its axis.
inline double diskFormFactor(double r, double h, double a) {
  if (a < 1e-9) return r * r / (r * r + h * h);
  const double H = h / a, R = r / a, Z = 1.0 + H * H + R * R;
  return 0.5 * (1.0 - (Z - 2.0 * R * R) / std::sqrt(Z * Z - 4.0 * R * R));
}

// To a parallel rectangle at height h whose corner is straight above the point, sides x and y
// (signed: the function is odd in both).
inline double cornerFormFactor(double x, double y, double h) {
  const double pi = 3.14159265358979323846;
  const double X = x / h, Y = y / h, sx = std::sqrt(1.0 + X * X), sy = std::sqrt(1.0 + Y * Y);
  return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2.0 * pi);
}

// To a parallel rectangle [x0, x1] x [z0, z1] (relative to the point) at height h, by the
// corners' signs.
inline double rectFormFactor(double x0, double x1, double z0, double z1, double h) {
  return cornerFormFactor(x1, z1, h) - cornerFormFactor(x0, z1, h) - cornerFormFactor(x1, z0, h) + cornerFormFactor(x0, z0, h);
}

}  // namespace tl::test
