// The GGX microfacet terms the shared BRDF (shared/shading.h) is built from, with nothing that
// depends on its precomputed tables, so the program that makes those tables
// (shaders/generator/brdf_tables.cpp) evaluates exactly the lobe the shaders evaluate.
//
// Contract (all cosines clamped by the caller; alpha = roughness^2 > 0):
//   tlGgxD(nh, alpha)                     GGX / Trowbridge-Reitz normal distribution D(h)
//   tlGgxDOfHalfVector(n, h, alpha)       the same from the vectors, accurate for the sharpest lobes
//   tlSmithVisibility(nl, nv, alpha)      height-correlated Smith V = G2 / (4 n.l n.v) (Heitz 2014)
//   tlSmithG1(nv, alpha)                  Smith masking G1 of one direction (the VNDF's normaliser)
//   tlSchlickWeight(vh)                   (1 - v.h)^5
//   tlFresnelSchlick(f0, vh)              f0 + (1 - f0) (1 - v.h)^5
//   tlFresnelAverage(f0)                  2 int F(mu) mu dmu = f0 + (1 - f0) / 21 (Schlick, closed form)
//   tlSampleGgxVisibleNormal(v, alpha, u) a half vector from the distribution of normals visible from
//                                         v (local frame, normal +z), pdf G1(v) max(v.h, 0) D(h) / v.z
//                                         (Dupuy & Benyoub 2023: a spherical cap in the stretched space)
#ifndef TL_SHARED_MICROFACET_H
#define TL_SHARED_MICROFACET_H
#include "common.h"

TL_BEGIN
TL_FN float tlGgxD(float nh, float alpha) {
  float a2 = alpha * alpha;
  float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

// 1 - n.h^2 taken as |n x h|^2: near the lobe's peak n.h rounds to within 6e-8 of 1, which is
// several percent of alpha^2 at the smallest roughness (1 + n.h^2 (alpha^2 - 1) cancels).
TL_FN float tlGgxDOfHalfVector(vec3 n, vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float nh = max(dot(n, h), 0.0f);
  vec3 c = cross(n, h);
  float d = nh * nh * a2 + dot(c, c);
  return a2 / (kPi * max(d * d, 1e-30f));
}

TL_FN float tlSmithVisibility(float nl, float nv, float alpha) {
  float a2 = alpha * alpha;
  float gv = nl * sqrt(nv * nv * (1.0f - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0f - a2) + a2);
  return 0.5f / max(gv + gl, 1e-7f);
}

TL_FN float tlSmithG1(float nv, float alpha) {
  float a2 = alpha * alpha;
  return 2.0f * nv / max(nv + sqrt(a2 + (1.0f - a2) * nv * nv), 1e-7f);
}

TL_FN float tlSchlickWeight(float vh) {
  float m = 1.0f - clamp(vh, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

TL_FN vec3 tlFresnelSchlick(vec3 f0, float vh) { return f0 + (vec3(1.0f) - f0) * tlSchlickWeight(vh); }

TL_FN vec3 tlFresnelAverage(vec3 f0) { return f0 + (vec3(1.0f) - f0) * (1.0f / 21.0f); }

TL_FN vec3 tlSampleGgxVisibleNormal(vec3 v, float alpha, vec2 u) {
  // Stretch the view so the GGX ellipsoid becomes a hemisphere; the visible normals of a
  // hemisphere seen from a direction are uniform on the spherical cap around it.
  vec3 vs = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
  float phi = 2.0f * kPi * u.x;
  float z = (1.0f - u.y) * (1.0f + vs.z) - vs.z;
  float sinTheta = sqrt(clamp(1.0f - z * z, 0.0f, 1.0f));
  vec3 h = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + vs;
  // Unstretch the normal.
  return normalize(vec3(alpha * h.x, alpha * h.y, max(h.z, 0.0f)));
}
TL_END
#endif
