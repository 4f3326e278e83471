// Packing shared by C++ and GLSL: octahedral unit vectors (G-buffer normals).
#ifndef TL_SHARED_PACKING_H
#define TL_SHARED_PACKING_H
#include "common.h"

TL_BEGIN
TL_FN vec2 tlSignNotZero(vec2 v) { return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f); }

// Unit vector -> [-1,1]^2 (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors"): project onto the octahedron, fold the lower half outwards.
TL_FN vec2 tlOctEncode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = vec2(n.x, n.y) / max(l1, 1e-20f);
  if (n.z < 0.0f) p = (vec2(1.0f) - abs(vec2(p.y, p.x))) * tlSignNotZero(p);
  return p;
}

TL_FN vec3 tlOctDecode(vec2 e) {
  vec3 n = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}
TL_END
#endif
