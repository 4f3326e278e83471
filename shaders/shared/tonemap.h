// Display mapping shared by C++ and GLSL: exposure (shared/color.h tlExposureScale) then ACES.
//
// Contract: both curves take exposed scene-linear Rec.709/sRGB-primaries radiance (negative
// values are treated as 0) and return DISPLAY-LINEAR values in [0,1]; sRGB-encode
// (tlLinearToSrgb) before writing an 8-bit image.
//   tlTonemapAces(c)           Hill's "ACESFitted" (RRT + sRGB ODT fit with the input/output
//                              matrices): the one the renderer uses. Black -> 0; grey input
//                              reaches 1.0 at about 25.7.
//   tlTonemapAcesNarkowicz(c)  Narkowicz 2015 fit of the ACES luminance curve, applied per
//                              channel, raw (no 0.6 pre-scale); for comparison. No gamut
//                              matrices, so more saturated; reaches 1.0 at about 7.2.
#ifndef TL_SHARED_TONEMAP_H
#define TL_SHARED_TONEMAP_H
#include "common.h"

TL_BEGIN
// glm and GLSL mat3 are both column-major and both fill the 9-float constructor column by
// column, so the same literals mean the same matrix in both languages. Hill writes these as
// HLSL rows for mul(M, v); each triple below is one of his COLUMNS, so M * v here equals
// his mul(M, v). Both matrices preserve white: each of Hill's rows sums to 1.
TL_FN mat3 tlAcesInputMatrix() {  // sRGB linear -> ACES fit space (includes the RRT saturation)
  return mat3(0.59719f, 0.07600f, 0.02840f, 0.35458f, 0.90834f, 0.13383f, 0.04823f, 0.01566f, 0.83777f);
}
TL_FN mat3 tlAcesOutputMatrix() {  // ODT fit space -> sRGB linear (includes the ODT desaturation)
  return mat3(1.60475f, -0.10208f, -0.00327f, -0.53108f, 1.10813f, -0.07276f, -0.07367f, -0.00605f, 1.07602f);
}

// The RRT+ODT rational fit by Stephen Hill (BakingLab, ACES.hlsl).
TL_FN vec3 tlRrtAndOdtFit(vec3 v) {
  vec3 a = v * (v + 0.0245786f) - 0.000090537f;
  vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
  return a / b;
}

TL_FN vec3 tlTonemapAces(vec3 linear) {
  vec3 c = tlAcesInputMatrix() * max(linear, vec3(0.0f));
  c = tlRrtAndOdtFit(c);
  c = tlAcesOutputMatrix() * c;
  return clamp(c, vec3(0.0f), vec3(1.0f));
}

// Krzysztof Narkowicz, "ACES Filmic Tone Mapping Curve" (2015): x(2.51x+0.03) / (x(2.43x+0.59)+0.14).
TL_FN vec3 tlTonemapAcesNarkowicz(vec3 linear) {
  vec3 x = max(linear, vec3(0.0f));
  vec3 y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return clamp(y, vec3(0.0f), vec3(1.0f));
}
TL_END
#endif
