// Display mapping shared by C++ and GLSL: exposure then ACES.
#ifndef TL_SHARED_TONEMAP_H
#define TL_SHARED_TONEMAP_H
#include "common.h"

TL_BEGIN
// ACES RRT+ODT fit by Stephen Hill ("ACESFitted"): sRGB-linear in, display-linear [0,1]
// out (then sRGB-encode for 8-bit). The input matrix maps sRGB to the ACES fit space and
// includes the RRT's saturation; the output matrix maps back. glm and GLSL mat3 are both
// column-major with the same constructor order, so these literals mean the same thing.
TL_FN vec3 tlRrtAndOdtFit(vec3 v) {
  vec3 a = v * (v + 0.0245786f) - 0.000090537f;
  vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
  return a / b;
}
TL_FN vec3 tlTonemapAces(vec3 linear) {
  const mat3 acesIn = mat3(0.59719f, 0.07600f, 0.02840f, 0.35458f, 0.90834f, 0.13383f, 0.04823f, 0.01566f, 0.83777f);
  const mat3 acesOut = mat3(1.60475f, -0.10208f, -0.00327f, -0.53108f, 1.10813f, -0.07276f, -0.07367f, -0.00605f, 1.07602f);
  vec3 c = acesIn * max(linear, vec3(0.0f));
  c = tlRrtAndOdtFit(c);
  c = acesOut * c;
  return clamp(c, vec3(0.0f), vec3(1.0f));
}
TL_END
#endif
