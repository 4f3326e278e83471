// The ray-tracing self-test (gpu/self_test.cpp): a 4x4 grid of rays shot down -Z from z = 1
// at one triangle in the plane z = 0 covering x + y < 0.01. Hit pixels store the hit
// distance (1.0), missed ones kSelfTestMiss.
#ifndef TL_SHARED_SELFTEST_H
#define TL_SHARED_SELFTEST_H
#include "common.h"

TL_BEGIN
TL_CONST uint kSelfTestSize = 4;
TL_CONST float kSelfTestMiss = -1.0f;
TL_CONST uint kSelfTestBindingScene = 0;
TL_CONST uint kSelfTestBindingOutput = 1;

// Where ray (x, y) starts; shared so the CPU knows which rays must hit.
TL_FN vec2 tlSelfTestRayXY(uint x, uint y) {
  return vec2((float(x) + 0.5f) / float(kSelfTestSize) * 2.0f - 1.0f, (float(y) + 0.5f) / float(kSelfTestSize) * 2.0f - 1.0f);
}
TL_END
#endif
