// Surface shading shared by the composite, the reference path tracer and the CPU tests:
// Lambert diffuse + GGX specular (height-correlated Smith, Schlick Fresnel), metallic
// workflow, and the split-sum environment term for a uniform sky.
#ifndef TL_SHARED_SHADING_H
#define TL_SHARED_SHADING_H
#include "common.h"

TL_BEGIN
struct SurfaceParams {
  vec3 diffuse;     // Lambert albedo: baseColor * (1 - metallic)
  vec3 f0;          // specular reflectance at normal incidence
  float alpha;      // GGX alpha = roughness^2, clamped away from 0
};

TL_FN SurfaceParams tlSurface(vec3 baseColor, float roughness, float metallic) {
  SurfaceParams s;
  s.diffuse = baseColor * (1.0f - metallic);
  s.f0 = mix(vec3(0.04f), baseColor, metallic);
  float r = clamp(roughness, 0.045f, 1.0f);  // a perfect mirror has no finite GGX lobe
  s.alpha = r * r;
  return s;
}

TL_FN float tlGgxD(float nh, float alpha) {
  float a2 = alpha * alpha;
  float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

// Height-correlated Smith visibility V = G / (4 n.l n.v) (Heitz 2014).
TL_FN float tlSmithVisibility(float nl, float nv, float alpha) {
  float a2 = alpha * alpha;
  float gv = nl * sqrt(nv * nv * (1.0f - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0f - a2) + a2);
  return 0.5f / max(gv + gl, 1e-7f);
}

TL_FN vec3 tlFresnelSchlick(vec3 f0, float vh) {
  float f = pow(1.0f - clamp(vh, 0.0f, 1.0f), 5.0f);
  return f0 + (vec3(1.0f) - f0) * f;
}

// BRDF times pi-free convention: returns f(l, v), so radiance = f * E * n.l for a light
// of irradiance E arriving from l.
TL_FN vec3 tlBrdf(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  float nl = max(dot(n, l), 0.0f);
  float nv = max(dot(n, v), 1e-4f);
  vec3 hv = v + l;
  float hl = length(hv);
  vec3 h = hl > 1e-7f ? hv / hl : n;
  float nh = max(dot(n, h), 0.0f);
  float vh = max(dot(v, h), 0.0f);
  vec3 spec = tlGgxD(nh, s.alpha) * tlSmithVisibility(nl, nv, s.alpha) * tlFresnelSchlick(s.f0, vh);
  return s.diffuse * kInvPi + spec;
}

// Directional albedo of the specular lobe under uniform incident radiance: the split-sum
// environment BRDF, analytic fit by Karis ("Physically Based Shading on Mobile", 2014).
// Multiply by a uniform sky radiance L to get the reflected specular radiance.
TL_FN vec3 tlEnvironmentSpecular(SurfaceParams s, float nv) {
  float roughness = sqrt(s.alpha);
  vec4 c0 = vec4(-1.0f, -0.0275f, -0.572f, 0.022f);
  vec4 c1 = vec4(1.0f, 0.0425f, 1.04f, -0.04f);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28f * nv)) * r.x + r.y;
  float scale = a004 * -1.04f + r.z;
  float bias = a004 * 1.04f + r.w;
  return s.f0 * scale + vec3(bias);
}
TL_END
#endif
