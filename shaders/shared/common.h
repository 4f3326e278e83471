// Included by C++ and GLSL. Maps GLSL types onto glm so one struct or function written
// here compiles in both languages (the idea of nvpro-samples' shared host/device header). Rules for shared code:
// no bool in a block, no vec3 in a block (std430 pads it), no swizzles, no in/out params.
#ifndef TL_SHARED_COMMON_H
#define TL_SHARED_COMMON_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace tl::shared {
using namespace glm;
using uint = uint32_t;
}  // namespace tl::shared
#define TL_BEGIN namespace tl::shared {
#define TL_END }
#define TL_CONST inline constexpr
#define TL_FN inline
#else
#define TL_BEGIN
#define TL_END
#define TL_CONST const
#define TL_FN
#endif

TL_BEGIN
TL_CONST float kPi = 3.14159265358979323846f;
TL_CONST float kInvPi = 0.31830988618379067154f;

TL_FN float tlSaturate(float x) { return clamp(x, 0.0f, 1.0f); }
TL_FN float tlLuminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }
TL_END

#endif
