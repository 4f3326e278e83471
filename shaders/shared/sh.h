// L1 spherical harmonics of luma plus scalar chroma, the irradiance encoding of Metro Exodus
// (GDC 2019, "Irradiance storage & encoding"): RGB -> YCoCg, Y as 4 L1 SH coefficients
// (RGBA16F), CoCg as 2 scalars (RG16F). Shared by C++ and GLSL.
//
// Basis and order. Real SH with Y00 = 0.282095 (1/(2 sqrt(pi))) and the three l=1 functions
// Y1 * (x, y, z), Y1 = 0.488603 (sqrt(3)/(2 sqrt(pi))). shY stores (L0, L1x, L1y, L1z): NOT the
// usual m = -1, 0, 1 order (y, z, x), so the L1 part is shY.yzw read as an x,y,z vector and
// dot(L1, direction) needs no reordering. A radiance function is reconstructed as
//   L(w) = Y00 * shY.x + Y1 * dot(vec3(shY.y, shY.z, shY.w), w).
//
// Chroma. coCg holds the L0 projection of Co and Cg (same weighting as shY.x), so coCg / shY.x
// is the chroma-to-luma ratio of the mean incoming radiance. Evaluate and resolve keep that
// ratio: chroma = (coCg / shY.x) * resolved Y. The colour is therefore direction-independent
// (the price of Metro's 96 bits): red light from the left and blue from the right give purple
// on both sides, at the correct luma per side.
//
// Projection. tlShProjectRadiance(dir, L) is one sample of unit solid-angle weight; the caller
// scales by its Monte Carlo weight (1/pdf, 4 pi / N for uniform sphere samples, ...) with
// tlShScale, sums with tlShAdd, and blends over time with tlShLerp (everything is linear).
//
// Irradiance. Convolving with the clamped cosine max(0, n.w) multiplies band l by A_l
// (Ramamoorthi & Hanrahan 2001): A0 = pi, A1 = 2 pi / 3. So
//   E(n) = A0 Y00 * shY.x + A1 Y1 * dot(L1, n) = 0.886226 * shY.x + 1.023326 * dot(L1, n),
// the two Metro constants being exactly pi * Y00 = sqrt(pi)/2 and (2 pi/3) * Y1 = sqrt(pi/3).
// Checks: uniform radiance L gives E = pi L for every n; a single unit-weight sample of
// radiance L from d gives E(d) = (1/4 + 1/2) L = 0.75 L (exact: L; L1 truncation), E(-d) =
// -0.25 L, clamped to 0. Negative results (ringing) are clamped to 0.
//
// Contract:
//   tlShZero / tlShMake / tlShAdd / tlShScale / tlShLerp   construction and linear algebra
//   tlShProjectRadiance(dir, rgb)      one sample (dir unit length) -> SH
//   tlShEvaluate(sh, dir)              RGB radiance estimate towards dir (>= 0)
//   tlShResolveIrradiance(sh, n)       RGB irradiance on a surface with unit normal n (>= 0)
//   tlShResolveLuma(sh, n)             its luma
//   tlShDominantDirection(sh, fallback)  normalize(L1), or fallback when L1 is ~0
//   tlShDirectionality(sh)             |L1| / (sqrt(3) L0) in [0,1]: 0 uniform, 1 single direction
//   tlShL1(sh), tlShLumaToRgb(sh, y)   helpers: the L1 vector; a luma value -> RGB at sh's chroma
//   tlShFitHalf(sh)                    the SH scaled as a whole into the half-float range
//   tlShHemisphereCoverage(cos, a)     what a uniform sky sampled over one normal's hemisphere
//                                      resolves to at a normal cos away, relative (see below)
//
// Storage. The SH and chroma live in RGBA16F / RG16F images, whose largest value is 65504. A
// store saturates each channel on its own: next to an emitter of 1e4 or more the luma L0
// saturated while the smaller chroma did not, the stored colour (L0, Co, Cg) then has a
// negative RGB channel, and every resolve of it gave negative radiance (down to -49,408 in
// the rt path). Whoever stores a freshly computed SH stores tlShFitHalf(sh): one factor for all
// six values keeps the colour and the direction, and only darkens what the format cannot hold.
// Sums with non-negative weights of fitted values (accumulation, denoising) stay in range.
#ifndef TL_SHARED_SH_H
#define TL_SHARED_SH_H
#include "color.h"
#include "common.h"

TL_BEGIN
TL_CONST float kShY00 = 0.282095f;             // 1 / (2 sqrt(pi))
TL_CONST float kShY1 = 0.488603f;              // sqrt(3) / (2 sqrt(pi))
TL_CONST float kShIrradianceL0 = 0.886226f;    // pi * kShY00
TL_CONST float kShIrradianceL1 = 1.023326f;    // (2 pi / 3) * kShY1
TL_CONST float kShDirectionalityNorm = 0.577350f;  // kShY00 / kShY1 = 1 / sqrt(3)
TL_CONST float kShHalfMax = 65504.0f;          // the largest half float

struct ShLumaCoCg {
  vec4 shY;   // luma SH: (L0, L1x, L1y, L1z)
  vec2 coCg;  // chroma, projected on the L0 band only
};

TL_FN ShLumaCoCg tlShMake(vec4 shY, vec2 coCg) {
  ShLumaCoCg s;
  s.shY = shY;
  s.coCg = coCg;
  return s;
}
TL_FN ShLumaCoCg tlShZero() { return tlShMake(vec4(0.0f), vec2(0.0f)); }
TL_FN ShLumaCoCg tlShAdd(ShLumaCoCg a, ShLumaCoCg b) { return tlShMake(a.shY + b.shY, a.coCg + b.coCg); }
TL_FN ShLumaCoCg tlShScale(ShLumaCoCg a, float s) { return tlShMake(a.shY * s, a.coCg * s); }
TL_FN ShLumaCoCg tlShLerp(ShLumaCoCg a, ShLumaCoCg b, float t) {
  return tlShMake(mix(a.shY, b.shY, t), mix(a.coCg, b.coCg, t));
}

TL_FN vec3 tlShL1(ShLumaCoCg sh) { return vec3(sh.shY.y, sh.shY.z, sh.shY.w); }

TL_FN ShLumaCoCg tlShProjectRadiance(vec3 direction, vec3 rgbRadiance) {
  vec3 ycocg = tlRgbToYCoCg(rgbRadiance);
  vec4 shY = ycocg.x * vec4(kShY00, kShY1 * direction.x, kShY1 * direction.y, kShY1 * direction.z);
  return tlShMake(shY, vec2(ycocg.y, ycocg.z) * kShY00);
}

// Luma -> RGB keeping the mean radiance's chroma-to-luma ratio (see the header comment). The
// max() removes what half-float rounding of a saturated colour leaves below zero (a pure
// green's red channel, Y + Co - Cg, rounds to about -1e-3 of Y); a colour stored out of range
// is prevented by tlShFitHalf, not hidden here.
TL_FN vec3 tlShLumaToRgb(ShLumaCoCg sh, float y) {
  float k = sh.shY.x > 1e-20f ? y / sh.shY.x : 0.0f;
  return max(tlYCoCgToRgb(vec3(y, sh.coCg.x * k, sh.coCg.y * k)), vec3(0.0f));
}

TL_FN ShLumaCoCg tlShFitHalf(ShLumaCoCg sh) {
  vec4 a = abs(sh.shY);
  float largest = max(max(max(a.x, a.y), max(a.z, a.w)), max(abs(sh.coCg.x), abs(sh.coCg.y)));
  return largest > kShHalfMax ? tlShScale(sh, kShHalfMax / largest) : sh;
}

TL_FN vec3 tlShEvaluate(ShLumaCoCg sh, vec3 direction) {
  float y = max(kShY00 * sh.shY.x + kShY1 * dot(tlShL1(sh), direction), 0.0f);
  return tlShLumaToRgb(sh, y);
}

// The luma of the irradiance on a surface with unit normal n (>= 0).
TL_FN float tlShResolveLuma(ShLumaCoCg sh, vec3 normal) {
  return max(kShIrradianceL0 * sh.shY.x + kShIrradianceL1 * dot(tlShL1(sh), normal), 0.0f);
}
TL_FN vec3 tlShResolveIrradiance(ShLumaCoCg sh, vec3 normal) { return tlShLumaToRgb(sh, tlShResolveLuma(sh, normal)); }

TL_FN vec3 tlShDominantDirection(ShLumaCoCg sh, vec3 fallback) {
  vec3 l1 = tlShL1(sh);
  float len = length(l1);
  return len > 1e-20f ? l1 / len : fallback;
}

// The directionality of a uniform sky of radiance L sampled by cosine over the hemisphere of n
// with the RT path's sample weight (shared/rt.h tlRtShSampleWeight): exact, the SH's mean is
// the projection of L cos / (1/4 + cos/2) over the hemisphere.
TL_CONST float kShOpenSkyDirectionality = 0.609389f;  // (ln 3 / 2) / (2 - ln 3)

// An SH gathered over the hemisphere of one normal, resolved at another normal cos(theta)
// away, misses the directions below the first hemisphere that lie above the second. For a
// uniform sky of directionality a (|L1| = sqrt(3) a L0 along the first normal; E(n) =
// 0.886226 L0 + 1.023326 L1.n) the resolved irradiance is, relative to the first normal's,
//   (1 + 2 a max(cos, 0)) / (1 + 2 a).
// A filter that mixes SH of different normals divides by its weighted mean of this (the RT
// denoiser, the legacy upsample): directions a sample never saw then count with the radiance
// of those it did, which is exact where the light is uniform (the white furnace).
TL_FN float tlShHemisphereCoverage(float cosTheta, float openSkyDirectionality) {
  return (1.0f + 2.0f * openSkyDirectionality * max(cosTheta, 0.0f)) / (1.0f + 2.0f * openSkyDirectionality);
}

// For non-negative radiance |L1| <= sqrt(3) L0, with equality only for a single direction.
// Metro maps (1 - directionality) to extra roughness for the specular lobe.
TL_FN float tlShDirectionality(ShLumaCoCg sh) {
  return sh.shY.x > 1e-20f ? clamp(length(tlShL1(sh)) * kShDirectionalityNorm / sh.shY.x, 0.0f, 1.0f) : 0.0f;
}
TL_END
#endif
