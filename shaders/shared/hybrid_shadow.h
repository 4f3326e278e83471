// Hybrid ray-traced sun shadows (GameWorks HRTS, GDC 2015): the pass shadow.sun.hybrid
// (common/sun_shadow_hybrid.comp) and the composite's use of its output.
#ifndef TL_SHARED_HYBRID_SHADOW_H
#define TL_SHARED_HYBRID_SHADOW_H
#include "common.h"

TL_BEGIN
// Bindings of shadow.sun.hybrid (set 0; the frame constants at kBindingFrame).
TL_CONST uint kHybridShadowNormal = 1;
TL_CONST uint kHybridShadowDepth = 2;
TL_CONST uint kHybridShadowMap = 3;       // the sun's shadow map, comparison sampler (PCSS filter)
TL_CONST uint kHybridShadowMapDepth = 4;  // the same map, plain sampler (PCSS blocker search)
TL_CONST uint kHybridShadowTlas = 5;      // the path's top level
TL_CONST uint kHybridShadowOutput = 6;    // r16f: the sun's visibility, 0..1 (0 where the sun is behind the surface)

struct HybridShadowPush {
  // The blend: where the true penumbra (2 tan(sun radius) x blocker distance) is narrower than
  // this many shadow-map texels the map cannot draw it, and the ray's hard shadow takes over;
  // linear up to it, the filtered map beyond.
  float hardPenumbraTexels;
  uint pad0;
  uint pad1;
  uint pad2;
};
TL_END
#endif
