// Colour temperature: the colour of a black body at T kelvin as Twinlight's linear RGB
// (Rec.709 primaries, D65 white), for lights given a temperature instead of an RGB colour.
//
// The approximation, stated: Planck's law integrated (1 nm steps, 360-830 nm) against the CIE
// 1931 2-degree colour-matching functions in Wyman, Sloan and Shirley's multi-lobe Gaussian fit
// (JCGT 2013; within about 1% of the tabulated functions), XYZ to linear sRGB, channels below 0
// (deep red temperatures lie outside the sRGB gamut) clamped to 0, scaled to luminance 1: the
// colour multiplies a light's intensity without changing its photometric value (lux, candela).
#pragma once

#include <glm/glm.hpp>

namespace tl::scene {

inline constexpr double kMinColorTemperature = 1000.0;   // kelvin: candle flame is ~1850 K
inline constexpr double kMaxColorTemperature = 40000.0;  // kelvin: clear blue sky is ~15000-27000 K

// CIE 1931 xyY chromaticity (x, y) of a black body at `kelvin` (the fit above).
glm::dvec2 blackBodyChromaticity(double kelvin);

// Linear Rec.709 RGB of luminance 1 (0.2126 R + 0.7152 G + 0.0722 B = 1). `kelvin` within
// [kMinColorTemperature, kMaxColorTemperature]; the caller checks the range.
glm::vec3 colorTemperatureToRgb(double kelvin);

}  // namespace tl::scene
