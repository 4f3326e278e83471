// The pass builder's own test shader (shaders/selftest/optional_input.comp): an optional
// sampled input, told to the shader by a push constant, and one output. Shared by C++ and GLSL.
#ifndef TL_SHARED_PASS_BUILDER_TEST_H
#define TL_SHARED_PASS_BUILDER_TEST_H
#include "common.h"

TL_BEGIN
TL_CONST uint kOptionalInputSource = 0u;  // sampler2D, R32F; may be absent
TL_CONST uint kOptionalInputResult = 1u;  // image2D r32f, written

struct OptionalInputPush {
  uint present;    // 1: the source is bound; 0: write `fallback`
  float fallback;  // the value written without a source
};
TL_END

#endif
