// Robust ray origins: move a hit point off its surface along the geometric normal by an
// amount that scales with the point's magnitude, in integer ULPs of its coordinates
// (Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
// Gems, 2019). Works at any distance from the origin of the (camera-relative) space. Near that
// origin, where ULPs vanish, the offset is a fixed share of the scene's extent `scale`
// (Wächter & Binder's 1/32 and 1/65536 are those shares of a 10 unit scene), so a scene drawn
// at any scale leaves its surfaces by the same share of itself.
#ifndef TL_SHARED_RAY_ORIGIN_H
#define TL_SHARED_RAY_ORIGIN_H
#include "common.h"

#ifdef __cplusplus
#include <bit>
#define TL_FLOAT_AS_INT(x) std::bit_cast<int32_t>(x)
#define TL_INT_AS_FLOAT(x) std::bit_cast<float>(x)
#else
#define TL_FLOAT_AS_INT(x) floatBitsToInt(x)
#define TL_INT_AS_FLOAT(x) intBitsToFloat(x)
#endif

TL_BEGIN
TL_CONST float kRayOriginNear = 1.0f / 320.0f;         // x scale: below this magnitude, a fixed offset
TL_CONST float kRayOriginFloatScale = 1.0f / 655360.0f;  // x scale: that offset
TL_CONST float kRayOriginIntScale = 256.0f;

TL_FN float tlOffsetComponent(float p, float n, float scale) {
  if (abs(p) < kRayOriginNear * scale) return p + kRayOriginFloatScale * scale * n;
  // Only here, away from zero, is the ULP step taken: at p = -0.0 the bits are INT_MIN and a
  // step towards -inf would overflow an int (UBSan found it in RayOrigin's unit test).
  int of = int(kRayOriginIntScale * n);
  return TL_INT_AS_FLOAT(TL_FLOAT_AS_INT(p) + (p < 0.0f ? -of : of));
}

// `n` is the geometric normal on the side the new ray leaves from; `scale` the scene's extent
// (FrameConstants::sceneScale).
TL_FN vec3 tlOffsetRayOrigin(vec3 p, vec3 n, float scale) {
  return vec3(tlOffsetComponent(p.x, n.x, scale), tlOffsetComponent(p.y, n.y, scale), tlOffsetComponent(p.z, n.z, scale));
}
TL_END
#endif
