// Indirect specular from the L1 SH of luma + CoCg (Metro Exodus, GDC 2019, "Decoding
// irradiance"): the per-pixel SH is a tiny cubemap, enough for the specular of metals, whose
// diffuse albedo is zero. Shared by the composite and the CPU tests.
//
// The SH the real-time paths accumulate covers the hemisphere above the surface (the RT
// path's cosine samples weighted by tlRtShSampleWeight, shared/rt.h), so even a uniform sky
// has a directionality: a_sky = (ln 3 / 2) / (2 - ln 3) = 0.6094 (exact: the SH's mean is
// the projection of L cos / (1/4 + cos/2) over the hemisphere; legacy's six cones: 0.6587,
// shared/legacy.h). The directionality a is remapped against the path's own,
// a' = saturate((a - a_sky) / (1 - a_sky)), and the resolved
// irradiance E(n) is split by a' into
//   - a uniform part, (1 - a') E(n): radiance (1 - a') E(n) / pi from the whole hemisphere,
//     whose specular is that radiance times the split-sum environment BRDF;
//   - a directional part, a' E(n): one light from the dominant direction d giving that
//     irradiance on the surface, shaded with the specular lobes (shared/shading.h: GGX and its
//     multiple-scattering compensation) at a roughness recomputed from a' (light
//     that is less directional is what a rougher lobe sees): alpha' = mix(1, alpha, a').
// Limits (unit-tested): an open uniform sky gives L times the environment term exactly; a
// single direction the GGX response to that light at the material's own roughness. The
// result is in the SH's chroma, like its diffuse resolve.
#ifndef TL_SHARED_SH_SPECULAR_H
#define TL_SHARED_SH_SPECULAR_H
#include "common.h"
#include "shading.h"
#include "sh.h"

TL_BEGIN
// How directional the light is beyond what an open uniform sky already shows (`openSky`: its
// directionality in this SH, kShOpenSkyDirectionality for the RT path's samples): 0 for the
// sky (or less directional light), 1 for a single direction.
TL_FN float tlShExcessDirectionality(ShLumaCoCg sh, float openSky) {
  return clamp((tlShDirectionality(sh) - openSky) / (1.0f - openSky), 0.0f, 1.0f);
}

// The roughness the directional part is shaded with: uniform light (a = 0) is seen as fully
// rough whatever the material, a single direction (a = 1) at the material's own alpha.
TL_FN float tlShSpecularAlpha(float alpha, float directionality) {
  return mix(1.0f, alpha, clamp(directionality, 0.0f, 1.0f));
}

TL_FN vec3 tlShSpecular(ShLumaCoCg sh, SurfaceParams s, vec3 n, vec3 v, float openSky) {
  if (!(sh.shY.x > 1e-20f)) return vec3(0.0f);
  float a = tlShExcessDirectionality(sh, openSky);
  float nv = max(dot(n, v), 1e-4f);
  float irradiance = tlShResolveLuma(sh, n);
  // Uniform part: its radiance times the environment BRDF.
  vec3 specular = tlEnvironmentSpecular(s, nv) * ((1.0f - a) * irradiance * kInvPi);
  // Directional part: GGX (specular lobe only) for a light from d giving a E(n) on the surface.
  vec3 d = tlShDominantDirection(sh, n);
  float nl = dot(n, d);
  if (a > 0.0f && nl > 1e-4f) {
    SurfaceParams lobe = tlSurfaceWithRoughness(s, sqrt(tlShSpecularAlpha(s.alpha, a)));
    // The specular lobes * (I n.l) with I n.l = a E(n).
    specular += tlBrdfSpecular(lobe, n, v, d) * (a * irradiance);
  }
  // Luma -> RGB at the SH's chroma, per channel of the BRDF's colour (F0 of a metal).
  return specular * tlShLumaToRgb(sh, 1.0f);
}
TL_END
#endif
