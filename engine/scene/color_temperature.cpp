#include "scene/color_temperature.h"

#include <algorithm>
#include <cmath>

namespace tl::scene {
namespace {

// One lobe of Wyman, Sloan and Shirley's fit: a Gaussian with a different width on each side.
double lobe(double lambda, double mean, double sigmaBelow, double sigmaAbove) {
  const double t = (lambda - mean) / (lambda < mean ? sigmaBelow : sigmaAbove);
  return std::exp(-0.5 * t * t);
}

glm::dvec3 colorMatching(double lambda) {
  const double x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
                   0.065 * lobe(lambda, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
  return {x, y, z};
}

// XYZ of black-body radiation at `kelvin`, up to a constant factor (only the colour matters).
glm::dvec3 blackBodyXyz(double kelvin) {
  constexpr double c2 = 1.438776877e-2;  // second radiation constant h c / k, metre kelvin
  glm::dvec3 xyz(0.0);
  for (double nm = 360.0; nm <= 830.0; nm += 1.0) {
    const double lambda = nm * 1e-9;
    const double planck = 1.0 / (std::pow(lambda, 5.0) * std::expm1(c2 / (lambda * kelvin)));
    xyz += planck * colorMatching(nm);
  }
  return xyz;
}

}  // namespace

glm::dvec2 blackBodyChromaticity(double kelvin) {
  const glm::dvec3 xyz = blackBodyXyz(kelvin);
  const double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum};
}

glm::vec3 colorTemperatureToRgb(double kelvin) {
  const glm::dvec3 xyz = blackBodyXyz(kelvin);
  const glm::dvec3 c = xyz / xyz.y;
  // CIE XYZ to linear sRGB (IEC 61966-2-1, D65 white).
  glm::dvec3 rgb(3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z, -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
                 0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z);
  rgb = glm::max(rgb, glm::dvec3(0.0));
  const double luminance = 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
  return glm::vec3(rgb / luminance);
}

}  // namespace tl::scene
