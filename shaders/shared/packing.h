// Packing shared by C++ and GLSL: octahedral unit vectors (G-buffer normals), 2x16-bit
// snorm words and half-float pairs.
//
// Contract:
//   tlOctEncode(n)            unit vector -> [-1,1]^2 (exact inverse of tlOctDecode up to rounding)
//   tlOctDecode(e)            [-1,1]^2 -> unit vector (any e in the square gives a unit vector)
//   tlPackSnorm2x16(v)        vec2 in [-1,1] -> uint, x in bits 0..15, y in bits 16..31; the same
//                             bits as GLSL/glm packSnorm2x16 (round half away from zero)
//   tlUnpackSnorm2x16(p)      inverse; -32768 decodes to -1 like the builtin
//   tlOctEncodeSnorm16(n)     unit vector -> one uint (oct + snorm16, the precise encoder)
//   tlOctDecodeSnorm16(p)     inverse
//   tlPackHalf2x16/tlUnpackHalf2x16   two floats <-> one uint of two IEEE halves (builtins)
//   tlRoundToHalf(v)          each component to the nearest IEEE half value (as a float), so a
//                             store to a 16-bit float image converts it exactly whatever the
//                             device's rounding mode
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

// Plain arithmetic rather than the builtin so rounding is pinned down on every GPU: the GLSL
// spec lets round() pick either way at .5, this rounds half away from zero (as glm does).
// Not floor(s + 0.5): that sum itself rounds up for s just below k + 0.5.
TL_FN uint tlSnorm16Bits(float x) {
  float s = clamp(x, -1.0f, 1.0f) * 32767.0f;
  float a = abs(s);
  float r = floor(a);
  r += a - r >= 0.5f ? 1.0f : 0.0f;  // a - floor(a) is exact for |a| < 2^23
  int i = int(s < 0.0f ? -r : r);
  return uint(i) & 0xFFFFu;
}
TL_FN float tlSnorm16Value(uint bits) {
  int i = int(bits << 16u) >> 16;  // sign-extend the low 16 bits (arithmetic shift in both languages)
  return max(float(i) / 32767.0f, -1.0f);
}
TL_FN uint tlPackSnorm2x16(vec2 v) { return tlSnorm16Bits(v.x) | (tlSnorm16Bits(v.y) << 16u); }
TL_FN vec2 tlUnpackSnorm2x16(uint p) { return vec2(tlSnorm16Value(p & 0xFFFFu), tlSnorm16Value(p >> 16u)); }

// Octahedral normal in one 32-bit word. Plain rounding of the encoded point (what an
// RG16_SNORM render target does) is off by up to ~0.0037 deg; this tries the four snorm16
// neighbours of the float encoding and keeps the one that decodes closest to n (Cigolle et
// al. 2014, "oct32P"): worst case ~0.0025 deg (measured, tests/unit/test_shared_math.cpp).
TL_FN uint tlOctEncodeSnorm16(vec3 n) {
  vec2 e = tlOctEncode(n) * 32767.0f;
  vec2 lo = floor(e);
  uint best = 0u;
  float bestErr = 8.0f;
  for (int i = 0; i < 4; ++i) {
    vec2 c = vec2(lo.x + float(i & 1), lo.y + float(i >> 1)) / 32767.0f;
    uint bits = tlPackSnorm2x16(c);
    // Squared chord, not 1 - dot: a float dot near 1 cannot resolve 0.01 deg.
    vec3 d = tlOctDecode(tlUnpackSnorm2x16(bits)) - n;
    float err = dot(d, d);
    if (err < bestErr) {
      bestErr = err;
      best = bits;
    }
  }
  return best;
}
TL_FN vec3 tlOctDecodeSnorm16(uint p) { return tlOctDecode(tlUnpackSnorm2x16(p)); }

// IEEE half pairs: the builtin has the same name and meaning in GLSL and glm.
TL_FN uint tlPackHalf2x16(vec2 v) { return packHalf2x16(v); }

// Vulkan lets a device convert floats to 16-bit floats by rounding to nearest or towards zero;
// an accumulation stored as halves each frame (x += (sample - x) / n) drifts down by up to n/2
// units in the last place under the latter (lavapipe: 0.4% at 32 frames, 1.1% at 128). Halves
// have 10 fraction bits; below 2^-14 their spacing is 2^-24. Clamped to the largest half.
TL_FN vec4 tlRoundToHalf(vec4 v) {
  vec4 a = abs(v);
  vec4 spacing = exp2(floor(log2(max(a, vec4(6.103515625e-05f)))) - 10.0f);
  return sign(v) * min(floor(a / spacing + 0.5f) * spacing, vec4(65504.0f));
}
TL_FN vec2 tlUnpackHalf2x16(uint p) { return unpackHalf2x16(p); }
TL_END
#endif
