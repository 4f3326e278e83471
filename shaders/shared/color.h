// Colour transforms shared by C++ and GLSL.
//
// Contract:
//   tlLinearToSrgb1/tlLinearToSrgb   linear [0,1] -> sRGB-encoded [0,1] (input clamped)
//   tlSrgbToLinear1/tlSrgbToLinear   sRGB-encoded [0,1] -> linear [0,1] (input clamped)
//   tlRgbToYCoCg / tlYCoCgToRgb      linear, unbounded (HDR safe), exact inverses of each other
//   tlExposureScale(ev)              multiplier applied to scene-linear radiance before tonemapping
//   Luminance (Rec.709 weights) is tlLuminance in common.h.
#ifndef TL_SHARED_COLOR_H
#define TL_SHARED_COLOR_H
#include "common.h"

TL_BEGIN
// The exact piecewise sRGB transfer function (IEC 61966-2-1).
TL_FN float tlLinearToSrgb1(float x) {
  x = clamp(x, 0.0f, 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}
TL_FN float tlSrgbToLinear1(float x) {
  x = clamp(x, 0.0f, 1.0f);
  return x <= 0.04045f ? x / 12.92f : pow((x + 0.055f) / 1.055f, 2.4f);
}
TL_FN vec3 tlLinearToSrgb(vec3 c) { return vec3(tlLinearToSrgb1(c.x), tlLinearToSrgb1(c.y), tlLinearToSrgb1(c.z)); }
TL_FN vec3 tlSrgbToLinear(vec3 c) { return vec3(tlSrgbToLinear1(c.x), tlSrgbToLinear1(c.y), tlSrgbToLinear1(c.z)); }

// YCoCg (the lossless-in-float variant used by Metro's irradiance encoding and by TAA):
// Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4; returned as (Y, Co, Cg).
// Inverse: R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg. Y is not luminance (Rec.709
// weights differ) but is >= 0 for non-negative RGB, and |Co|, |Cg| <= 2Y.
TL_FN vec3 tlRgbToYCoCg(vec3 c) {
  return vec3(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z, -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}
TL_FN vec3 tlYCoCgToRgb(vec3 y) { return vec3(y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z); }

// Exposure, in the units the session uses (engine/session: autoExposureEv, fc.exposure):
// ev = log2 of the scene-linear luminance that maps to 1.0 before the tonemapper, in the
// renderer's radiance units. scale = 2^-ev. This is not photographic EV100: a camera
// calibration would be 1 / (1.2 * 2^EV100) (ISO 100, K = 12.5, q = 0.65), i.e. ev here =
// EV100 + log2(1.2). +1 ev halves the image brightness.
TL_FN float tlExposureScale(float ev) { return exp2(-ev); }
TL_END
#endif
