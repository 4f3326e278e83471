// Sampling, BRDF terms and hashing shared by C++ and GLSL (ray-traced GI, reference paths,
// CPU tests).
//
// Directions from tlSample* are in a LOCAL frame with the normal on +z; tlBasisFromNormal /
// tlLocalToWorld take them to world space. u is a pair of independent uniforms in [0,1).
//
// Contract:
//   tlSampleConcentricDisk(u)        unit disk, area-uniform, low distortion (Shirley & Chiu 1997)
//   tlSampleCosineHemisphere(u)      pdf cos(theta)/pi (Malley: lift the concentric disk)
//   tlSampleUniformHemisphere(u)     pdf 1/(2 pi) = kUniformHemispherePdf
//   tlSampleUniformSphere(u)         pdf 1/(4 pi) = kUniformSpherePdf
//   tlSampleGgxHalfVector(u, alpha)  half vector, pdf D(h) cos(theta_h) = tlGgxHalfVectorPdf
//   tlBasisFromNormal(n)             mat3(t, b, n), right-handed orthonormal, branchless
//                                    (Duff et al. 2017); n must be unit length
//   tlLambertBrdf, tlSmithG2HeightCorrelated   BRDF terms not already in shared/microfacet.h;
//                                    GGX D (tlGgxD), the Smith visibility (tlSmithVisibility) and
//                                    Schlick Fresnel (tlFresnelSchlick) live there and are reused
//   tlPcgHash(x), tlPcg3d(v)         integer hashes (Jarzynski & Olano 2020, "Hash Functions for
//                                    GPU Rendering"): PCG-RXS-M-XS and pcg3d
//   tlUintToUnitFloat(x)             top 24 bits -> [0,1), exactly representable, never 1.0
//   tlRandom2(seed)                  two uniforms from a (pixel.x, pixel.y, frame*K+sample) seed
//   tlRadicalInverse2(i)             van der Corput in base 2: i's bits mirrored behind the point
#ifndef TL_SHARED_SAMPLING_H
#define TL_SHARED_SAMPLING_H
#include "common.h"
#include "microfacet.h"

TL_BEGIN
TL_CONST float kUniformSpherePdf = 0.07957747155f;      // 1 / (4 pi)
TL_CONST float kUniformHemispherePdf = 0.15915494309f;  // 1 / (2 pi)

TL_FN vec2 tlSampleConcentricDisk(vec2 u) {
  vec2 a = 2.0f * u - vec2(1.0f);
  if (a.x == 0.0f && a.y == 0.0f) return vec2(0.0f);
  float r, phi;
  if (abs(a.x) > abs(a.y)) {
    r = a.x;
    phi = (0.25f * kPi) * (a.y / a.x);
  } else {
    r = a.y;
    phi = 0.5f * kPi - (0.25f * kPi) * (a.x / a.y);
  }
  return r * vec2(cos(phi), sin(phi));
}

TL_FN vec3 tlSampleCosineHemisphere(vec2 u) {
  vec2 d = tlSampleConcentricDisk(u);
  return vec3(d.x, d.y, sqrt(max(1.0f - dot(d, d), 0.0f)));
}
TL_FN float tlCosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0f) * kInvPi; }

TL_FN vec3 tlSampleUniformSphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = sqrt(max(1.0f - z * z, 0.0f));
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

TL_FN vec3 tlSampleUniformHemisphere(vec2 u) {
  float z = u.x;
  float r = sqrt(max(1.0f - z * z, 0.0f));
  float phi = 2.0f * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// Inverse CDF of D(h) cos(theta_h): cos^2(theta) = (1 - u) / (1 + (alpha^2 - 1) u).
TL_FN vec3 tlSampleGgxHalfVector(vec2 u, float alpha) {
  float a2 = alpha * alpha;
  float cos2 = (1.0f - u.x) / (1.0f + (a2 - 1.0f) * u.x);
  float cosTheta = sqrt(clamp(cos2, 0.0f, 1.0f));
  float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
  float phi = 2.0f * kPi * u.y;
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}
TL_FN float tlGgxHalfVectorPdf(float nh, float alpha) { return tlGgxD(nh, alpha) * max(nh, 0.0f); }

// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal
// Basis, Revisited" (JCGT 6(1)). Columns: tangent, bitangent, normal; cross(t, b) = n.
TL_FN mat3 tlBasisFromNormal(vec3 n) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;  // copysign(1, n.z), with +0 -> +1
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  vec3 t = vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
  return mat3(t, bt, n);
}
TL_FN vec3 tlLocalToWorld(vec3 local, vec3 n) { return tlBasisFromNormal(n) * local; }

TL_FN vec3 tlLambertBrdf(vec3 albedo) { return albedo * kInvPi; }

// Height-correlated Smith masking-shadowing G2 (Heitz 2014, eq. 99) = 4 n.l n.v V.
TL_FN float tlSmithG2HeightCorrelated(float nl, float nv, float alpha) {
  return 4.0f * max(nl, 0.0f) * max(nv, 0.0f) * tlSmithVisibility(max(nl, 0.0f), max(nv, 0.0f), alpha);
}

TL_FN uint tlPcgHash(uint x) {
  uint state = x * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

TL_FN uvec3 tlPcg3d(uvec3 v) {
  v = v * 1664525u + uvec3(1013904223u);
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v = v ^ (v >> 16u);
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

TL_FN float tlUintToUnitFloat(uint x) { return float(x >> 8u) * (1.0f / 16777216.0f); }

TL_FN float tlRadicalInverse2(uint i) {
  // Reverse the 32 bits by swapping ever larger halves; the top 24 make an exact float.
  i = (i << 16u) | (i >> 16u);
  i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
  i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
  i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
  i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
  return tlUintToUnitFloat(i);
}

// Point k of the R2 sequence (Roberts 2018: the additive recurrence on the inverse powers of the
// plastic number) shifted by `offset` (fixed point; a random shift per pixel, Cranley-Patterson
// rotation): each point alone is uniform in the unit square, and any k consecutive points cover
// it about as evenly as k stratified ones, so a running mean over frames converges faster than
// with independent draws. Fixed point: exact for every k (a float k * alpha is not past 2^24).
TL_FN vec2 tlR2Point(uint k, uvec2 offset) {
  return vec2(tlUintToUnitFloat(offset.x + k * 0xC13FA9A9u), tlUintToUnitFloat(offset.y + k * 0x91E10DA5u));
}

TL_FN vec2 tlRandom2(uvec3 seed) {
  uvec3 h = tlPcg3d(seed);
  return vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y));
}

// A 4x4 ordered (Bayer) dither in (0, 1): the 16 cells of any aligned 4x4 block take the values
// (k + 0.5) / 16 once each, so a threshold test keeps the same fraction of every block.
TL_FN uint tlBayer2(uint x, uint y) { return (((x ^ y) & 1u) << 1u) | (y & 1u); }
TL_FN float tlOrderedDither4(uint x, uint y) {
  return (float(4u * tlBayer2(x, y) + tlBayer2(x >> 1u, y >> 1u)) + 0.5f) * (1.0f / 16.0f);
}

// Stochastic transparency's number for a ray crossing a surface (the any-hit shaders): a hash of
// the launch, the primitive, the hit distance, the ray's sample and the instance, so every ray
// and crossing draws afresh and a second any-hit call for the same crossing decides alike.
TL_FN float tlAlphaRayDither(uvec2 launch, uint primitive, float hitT, uint rayIndex, uint instance) {
  uvec3 h = tlPcg3d(uvec3(launch.x ^ (primitive * 0x9E3779B9u), launch.y ^ floatBitsToUint(hitT),
                          rayIndex ^ (instance << 16u)));
  return tlUintToUnitFloat(h.x);
}

// Stochastic transparency's number for a rasterized sample at pixel (x, y): the ordered dither,
// shifted by the golden ratio each frame when frames are averaged (TAA), so every pixel cycles
// through the thresholds; a still dither otherwise (no flicker where nothing averages it).
TL_FN float tlAlphaDither(uint x, uint y, uint frameIndex, bool framesAveraged) {
  float d = tlOrderedDither4(x, y);
  return framesAveraged ? fract(d + 0.6180340f * float(frameIndex & 1023u)) : d;
}
TL_END
#endif
