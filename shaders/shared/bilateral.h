// The edge-aware weight of the project's upsamples (legacy.upsample's depth weights, after
// INSIDE's depth-aware upsampling; ibuffer.upsample's plane and roughness weights): a sample
// that differs from the pixel by x weighs 1 / (1 + (x / tolerance)^2), half at the tolerance.
#ifndef TL_SHARED_BILATERAL_H
#define TL_SHARED_BILATERAL_H
#include "common.h"

TL_BEGIN
TL_FN float tlBilateralWeight(float difference, float tolerance) {
  float r = difference / tolerance;
  return 1.0f / (1.0f + r * r);
}
TL_END
#endif
