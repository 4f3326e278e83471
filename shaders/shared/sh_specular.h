// Indirect specular from the L1 SH of luma + CoCg (Metro Exodus, GDC 2019, "Decoding
// irradiance"): the per-pixel SH is a tiny cubemap, enough for the specular of metals, whose
// diffuse albedo is zero. Shared by the composite and the CPU tests.
//
// The SH is split by its directionality a = |L1| / (sqrt(3) L0) (shared/sh.h) into
//   - a uniform part holding (1 - a) of the incoming light: mean radiance (1 - a) L0 Y00,
//     whose specular is exactly that radiance times the split-sum environment BRDF;
//   - a directional part holding a of it, as one light from the dominant direction d whose
//     irradiance (facing it) is a L0 / Y00 (exact for light from a single direction), shaded
//     with GGX at a roughness recomputed from a: less directional light is what a rougher
//     lobe sees, alpha' = mix(1, alpha, a).
// Limits: a uniform SH gives the environment term exactly; a single-direction SH gives the
// GGX response to that light at the material's own roughness. The result is in the SH's
// chroma, like its diffuse resolve.
#ifndef TL_SHARED_SH_SPECULAR_H
#define TL_SHARED_SH_SPECULAR_H
#include "common.h"
#include "shading.h"
#include "sh.h"

TL_BEGIN
// The roughness the directional part is shaded with: uniform light (a = 0) is seen as fully
// rough whatever the material, a single direction (a = 1) at the material's own alpha.
TL_FN float tlShSpecularAlpha(float alpha, float directionality) {
  return mix(1.0f, alpha, clamp(directionality, 0.0f, 1.0f));
}

TL_FN vec3 tlShSpecular(ShLumaCoCg sh, SurfaceParams s, vec3 n, vec3 v) {
  if (!(sh.shY.x > 1e-20f)) return vec3(0.0f);
  float a = tlShDirectionality(sh);
  float nv = max(dot(n, v), 1e-4f);
  // Uniform part: mean radiance times the environment BRDF.
  float uniformLuma = (1.0f - a) * kShY00 * sh.shY.x;
  vec3 specular = tlEnvironmentSpecular(s, nv) * uniformLuma;
  // Directional part: GGX (specular lobe only) for a light from d.
  vec3 d = tlShDominantDirection(sh, n);
  float nl = dot(n, d);
  if (a > 0.0f && nl > 0.0f) {
    SurfaceParams lobe = s;
    lobe.diffuse = vec3(0.0f);
    lobe.alpha = tlShSpecularAlpha(s.alpha, a);
    float irradiance = a * sh.shY.x / kShY00;
    specular += tlBrdf(lobe, n, v, d) * (irradiance * nl);
  }
  // Luma -> RGB at the SH's chroma, per channel of the BRDF's colour (F0 of a metal).
  vec3 white = tlShLumaToRgb(sh, 1.0f);
  return specular * white;
}
TL_END
#endif
