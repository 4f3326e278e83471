// Redeferred shading (Fools Engine): the shared BRDF (shared/shading.h) split into sums of light
// that hold no material, the I-buffer, and the material pass that applies base colour,
// metalness and F0 once. docs/design/redeferred.md has the derivation.
//
// For a light of irradiance E_c = E n.l (visibility included) from l, the illumination passes add
//   Ldg  += E_c (1 - E_d(mu_i))          the diffuse layer's share of the light
//   Lsg1 += E_c D V                      the single-scattering lobe with F = 1
//   Lsg2 += E_c D V P                    the same times Schlick's weight P = (1 - v.h)^5
//   Lms  += E_c (1 - E(mu_i))            the multiple-scattering lobe's share
// D V, E(mu) and E_d(mu) depend on the roughness, the normal and the view only: the G-buffer's
// geometry, not its material. The material pass then reproduces the BRDF exactly:
//   L = diffuse (1 - E_d(mu_o)) / (pi (1 - E_d,avg)) Ldg             (f_diffuse)
//     + F0 Lsg1 + (1 - F0) Lsg2                                       (f_ss: F = F0 (1 - P) + P)
//     + F_ms (1 - E(mu_o)) / (pi (1 - E_avg)) Lms                     (f_ms, Kulla-Conty)
// The fourth sum, Lms, is this project's: the talk's BRDF had no multiple-scattering
// compensation, whose angular weight 1 - E(mu_i) is neither the diffuse layer's nor a lobe's.
#ifndef TL_SHARED_REDEFERRED_H
#define TL_SHARED_REDEFERRED_H
#include "common.h"
#include "shading.h"

TL_BEGIN
// Bindings of the I-buffer pass (ibuffer.light, set 0). Frame 0, BRDF tables kBindingBrdfTables,
// the light table kBindingLights; the path's inputs at the composite's numbers (8-10, 14-16).
TL_CONST uint kIbufferNormal = 2u;
TL_CONST uint kIbufferMaterial = 3u;
TL_CONST uint kIbufferDepth = 5u;
TL_CONST uint kIbufferShadow = 6u;
TL_CONST uint kIbufferShadowDepth = 11u;
TL_CONST uint kIbufferOutDg = 20u;   // rgba32f storage images: Ldg, Lsg1, Lsg2, Lms
TL_CONST uint kIbufferOutSg1 = 21u;
TL_CONST uint kIbufferOutSg2 = 22u;
TL_CONST uint kIbufferOutMs = 23u;
TL_CONST uint kIbufferLightsDg = 24u;  // the light table's share (lights.direct in redeferred form), sampled
TL_CONST uint kIbufferLightsSg1 = 25u;
TL_CONST uint kIbufferLightsSg2 = 26u;
TL_CONST uint kIbufferLightsMs = 27u;
// The passes that read sums of the I-buffer (redeferred.material and ibuffer.lightOnly the
// finished ones, ibuffer.upsample the pattern's) sample them at slots 24-27, named for them by
// what they hold. The material pass writes at kCompositeOutput like the composite, the
// light-only view at kIbufferLightOnlyOut. The lights pass in redeferred form writes its four
// sums at 20-23 and accumulates them (many lights) in 28-31.
TL_CONST uint kIbufferSumDg = 24u;   // ibuffer.Ldg ... Lms (or ibuffer.shaded.*), sampled
TL_CONST uint kIbufferSumSg1 = 25u;
TL_CONST uint kIbufferSumSg2 = 26u;
TL_CONST uint kIbufferSumMs = 27u;
TL_CONST uint kIbufferLightOnlyOut = 20u;  // rgba32f: ibuffer.lightOnly
TL_CONST uint kIbufferAccumDg = 28u;
TL_CONST uint kIbufferAccumSg1 = 29u;
TL_CONST uint kIbufferAccumSg2 = 30u;
TL_CONST uint kIbufferAccumMs = 31u;

// The illumination stage's shading rate (the `redeferredRate` setting): which pixels the
// illumination passes shade first. The rest are filled from them by ibuffer.upsample where the
// surface and the light are smooth, and shaded too (a second, refining run of the same passes)
// where they are not: across geometry edges and where the shaded neighbours' light disagrees
// (shadow edges, a lamp's falloff).
TL_CONST uint kIbufferPatternEvery = 0u;        // rate 1: every pixel
TL_CONST uint kIbufferPatternCheckerboard = 1u; // rate 1/2: pixels with x + y even
TL_CONST uint kIbufferPatternBlocks = 2u;       // rate 1/4: the top-left pixel of each 2x2 block
// What one run of an illumination pass shades (LightsPush/CompositePush ibufferStage).
TL_CONST uint kIbufferStageEvery = 0u;    // every pixel (rate 1)
TL_CONST uint kIbufferStagePattern = 1u;  // the pattern's pixels, dispatched densely
TL_CONST uint kIbufferStageRefine = 2u;   // the pixels ibuffer.upsample marked kIbufferRefined (ibuffer.light: and
                                          // the filled ones copied, so its output is the whole I-buffer)
// ibuffer.refine's values: how each pixel's I-buffer was made.
TL_CONST float kIbufferShadedFirst = 0.0f;  // a pattern pixel (or the sky)
TL_CONST float kIbufferFilled = 1.0f;       // filled from its shaded neighbours
TL_CONST float kIbufferRefined = 2.0f;      // shaded at full rate (an edge)
// Bindings of ibuffer.upsample (set 0): the pattern's sums (ibuffer.shaded.*) sampled at
// kIbufferLights*, the filled ones (ibuffer.filled.*) written at kIbufferOut*, the G-buffer at
// kIbufferNormal/Material/Depth, the mark it writes here. The refining run of ibuffer.light
// samples the filled sums at kIbufferFilled* and the light table's refined share at kIbufferLights*.
TL_CONST uint kIbufferRefineMask = 32u;         // r32f storage image (ibuffer.refine)
TL_CONST uint kIbufferRefineMaskSampled = 33u;  // the same, sampled by the refining runs
TL_CONST uint kIbufferFilledDg = 34u;
TL_CONST uint kIbufferFilledSg1 = 35u;
TL_CONST uint kIbufferFilledSg2 = 36u;
TL_CONST uint kIbufferFilledMs = 37u;
TL_CONST uint kIbufferSunVisibility = 38u;  // r16f: shadow.sun.visibility (HRTS), with kCompositeHasSunVisibility

// ibuffer.upsample's edges: a shaded neighbour off this pixel's tangent plane by more than
// this share of the pixel's distance, at a normal's cosine below, or a roughness further than
// this, is another surface; neighbours whose diffuse or specular sums' luminance spread is more
// than kIbufferEdgeLight of the largest (above kIbufferLightFloor, W/m^2) straddle a change of
// light. Either way the pixel is shaded rather than filled.
TL_CONST float kIbufferEdgePlane = 0.02f;
TL_CONST float kIbufferEdgeCosine = 0.9f;
TL_CONST float kIbufferEdgeRoughness = 0.1f;
TL_CONST float kIbufferEdgeLight = 0.25f;
TL_CONST float kIbufferLightFloor = 1e-6f;
// The fill's normal weights, cosine^k: the specular sums vary faster with the normal.
TL_CONST float kIbufferDiffuseNormalPower = 8.0f;
TL_CONST float kIbufferSpecularNormalPower = 32.0f;
struct IbufferUpsamplePush {
  uint pattern;  // kIbufferPattern*
  uint pad0, pad1, pad2;
};

// Pattern of a rate: 1 -> every pixel, 0.5 -> checkerboard, 0.25 -> 2x2 blocks.
TL_FN uint tlIbufferPattern(float rate) {
  return rate >= 1.0f ? kIbufferPatternEvery : (rate >= 0.5f ? kIbufferPatternCheckerboard : kIbufferPatternBlocks);
}
// Whether pattern `pattern` shades pixel p first.
TL_FN bool tlIbufferShadedFirst(ivec2 p, uint pattern) {
  if (pattern == kIbufferPatternCheckerboard) return ((p.x + p.y) & 1) == 0;
  if (pattern == kIbufferPatternBlocks) return ((p.x | p.y) & 1) == 0;
  return true;
}
// The dense dispatch of the pattern's pixels: its grid for an image of `size`, and the pixel
// invocation q shades.
TL_FN uvec2 tlIbufferPatternGrid(uvec2 size, uint pattern) {
  if (pattern == kIbufferPatternCheckerboard) return uvec2((size.x + 1u) / 2u, size.y);
  if (pattern == kIbufferPatternBlocks) return uvec2((size.x + 1u) / 2u, (size.y + 1u) / 2u);
  return size;
}
TL_FN ivec2 tlIbufferPatternPixel(ivec2 q, uint pattern) {
  if (pattern == kIbufferPatternCheckerboard) return ivec2(2 * q.x + (q.y & 1), q.y);
  if (pattern == kIbufferPatternBlocks) return 2 * q;
  return q;
}

// One sum of the I-buffer per quantity (rgb: colour of the light).
struct IbufferSums {
  vec3 dg, sg1, sg2, ms;
};

TL_FN IbufferSums tlIbufferZero() {
  IbufferSums s;
  s.dg = vec3(0.0f);
  s.sg1 = vec3(0.0f);
  s.sg2 = vec3(0.0f);
  s.ms = vec3(0.0f);
  return s;
}

// The geometry's share of a surface: what the illumination passes may know (roughness, and
// whether the material override mode leaves a specular layer), no colour.
TL_FN SurfaceParams tlIbufferSurface(float roughness, uint materials) {
  if (materials == kMaterialsAuthored) return tlSurface(vec3(0.0f), roughness, 0.0f);
  return tlLambertSurface(vec3(0.0f));
}

// `sums` plus a light of irradiance `irradiance` on the surface (E n.l, visibility included) from l.
TL_FN IbufferSums tlIbufferAddLight(IbufferSums sums, SurfaceParams g, vec3 n, vec3 v, vec3 l, vec3 irradiance) {
  float nl = dot(n, l);
  if (!(nl > 0.0f)) return sums;
  float nv = max(dot(n, v), kBrdfMinCosine);
  vec2 split = tlSpecularAlbedoSplit(nl, g.roughness);
  sums.dg += irradiance * (1.0f - tlLayerAlbedo(g, split));
  if (g.specular == 0.0f) return sums;
  vec3 hv = v + l;
  float hl = length(hv);
  vec3 h = hl > 1e-7f ? hv / hl : n;
  float dv = tlGgxDOfHalfVector(n, h, g.alpha) * tlSmithVisibility(nl, nv, g.alpha);
  sums.sg1 += irradiance * dv;
  sums.sg2 += irradiance * (dv * tlSchlickWeight(max(dot(v, h), 0.0f)));
  sums.ms += irradiance * (1.0f - tlSingleScatteringAlbedo(split));
  return sums;
}

// `sums` plus diffuse irradiance from the whole hemisphere (the sky, a path's GI) as the diffuse
// layer sees it: f_diffuse integrated against light of any direction distribution whose
// cosine-weighted mean of 1 - E_d is 1 - E_d,avg, the uniform case tlEnvironmentDiffuse is
// exact for (and which the deferred composite uses for every indirect irradiance).
TL_FN IbufferSums tlIbufferAddIrradiance(IbufferSums sums, SurfaceParams g, vec3 irradiance) {
  sums.dg += irradiance * (1.0f - g.layerAverage);
  return sums;
}

// The sum of two I-buffers (light is additive) and one scaled (an estimate's weight).
TL_FN IbufferSums tlIbufferAdd(IbufferSums a, IbufferSums b) {
  a.dg += b.dg;
  a.sg1 += b.sg1;
  a.sg2 += b.sg2;
  a.ms += b.ms;
  return a;
}
TL_FN IbufferSums tlIbufferScale(IbufferSums a, float k) {
  a.dg *= k;
  a.sg1 *= k;
  a.sg2 *= k;
  a.ms *= k;
  return a;
}

// The material pass: the surface s (its geometry the I-buffer's) seen from cos theta = nv.
TL_FN vec3 tlIbufferResolve(SurfaceParams s, float nv, IbufferSums sums) {
  float c = max(nv, kBrdfMinCosine);
  vec2 split = tlSpecularAlbedoSplit(c, s.roughness);
  vec3 diffuse = s.diffuse * ((1.0f - tlLayerAlbedo(s, split)) * kInvPi / tlDiffuseLayerWeight(s)) * sums.dg;
  if (s.specular == 0.0f) return diffuse;
  vec3 single = s.f0 * sums.sg1 + (s.f90 - s.f0) * sums.sg2;
  vec3 multiple = s.msFresnel * ((1.0f - tlSingleScatteringAlbedo(split)) * kInvPi / max(1.0f - s.singleAverage, 1e-6f)) * sums.ms;
  return diffuse + single + multiple;
}

// The "light only" view: the I-buffer resolved against white (base colour 1, dielectric, the
// pixel's roughness; white Lambert in the override modes): the light the artist placed,
// without the materials. A white surface reflects all it receives, so this is also the most
// any material there could show.
TL_FN vec3 tlIbufferLightOnly(float roughness, uint materials, float nv, IbufferSums sums) {
  SurfaceParams white = materials == kMaterialsAuthored ? tlSurface(vec3(1.0f), roughness, 0.0f) : tlLambertSurface(vec3(1.0f));
  return tlIbufferResolve(white, nv, sums);
}
TL_END
#endif
