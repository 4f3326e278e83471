// The one surface BRDF of every lighting path, the reference path tracer and the CPU tests:
// glTF 2.0's metal-rough model made energy-conserving (docs/accuracy.md has the derivation).
//
//   f = mix(f_dielectric, f_metal, metallic)
//   f_metal      = f_ss(F0 = baseColor, F90 = 1) + f_ms(F0 = baseColor, F90 = 1)
//   f_dielectric = f_ss(F0_d, F90_d) + f_ms(F0_d, F90_d) + f_diffuse
//   f_ss(F0,F90) = D(h) V(l, v) F(v.h)             GGX, height-correlated Smith, Schlick's Fresnel
//                  F = F0 + (F90 - F0) (1 - v.h)^5
//   f_ms(F0,F90) = F_ms (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg))            (Kulla & Conty 2017)
//                  F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),  F_avg = F0 + (F90 - F0) / 21
//   f_diffuse    = baseColor / pi (1 - E_d(mu_o)) (1 - E_d(mu_i)) / (1 - E_d,avg)     (per channel)
//
// The dielectric's Fresnel is glTF's KHR_materials_ior and KHR_materials_specular (their
// defaults give F0_d = 0.04, F90_d = 1: glTF's core model):
//   F0_d  = min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular,   F90_d = specular
// (shared/scene.h tlDielectricFresnel; specular and specularColor are the factors times their
// textures). The G-buffer carries F0_d as one grey value (shared/gbuffer.h): a tinted specular
// colour shows in the reference, in grey in the G-buffer paths.
//
// E(mu) is the albedo of f_ss with F = 1 and E_avg its cosine-weighted average, so f_ss + f_ms
// reflects exactly what one microfacet bounce loses to masking: a white metal reflects all the
// light it receives at any roughness. E_d(mu) is the dielectric's whole specular albedo (f_ss +
// f_ms at F0 = 0.04): the diffuse layer gets exactly the energy the specular layer does not
// reflect, so a white dielectric also reflects everything, and the form stays reciprocal.
// A coloured F0_d makes E_d and the diffuse layer's weight coloured: each channel conserves
// energy on its own. It is glTF's fresnel_mix (diffuse weighted by 1 - F) with the Fresnel of one microfacet
// replaced by the albedo of the whole specular layer, which is what makes it conserve energy.
// E and E_avg come from tables the build computes (shared/brdf_lut.h); a shader that includes
// this file and shades reads them from binding kBindingBrdfTables of set 0 ("brdf.tables").
//
// A "Lambert" surface (tlLambertSurface: the diffuse and clay override modes) has no specular
// layer: f = albedo / pi.
//
// Layers glTF's extensions add: transmission through the diffuse layer (tlSurfaceTransmitting)
// and a clear coat over everything (tlSurfaceCoated); the G-buffer paths' surfaces have neither.
//
// Also here: the terms for a uniform environment (tlEnvironmentSpecular / tlEnvironmentDiffuse:
// the reflected radiance per unit of uniform incident radiance, exact for this BRDF), the
// hemispherical albedo, and sampling (the reference path tracer).
#ifndef TL_SHARED_SHADING_H
#define TL_SHARED_SHADING_H
#include "common.h"
#include "brdf_lut.h"
#include "gbuffer.h"
#include "material_mode.h"
#include "microfacet.h"
#include "sampling.h"
#ifdef __cplusplus
#include "shared/brdf_tables.h"
#endif

// The tables (shared/brdf_lut.h): the generated constant in C++, the brdf.tables buffer in GLSL.
#ifdef __cplusplus
TL_BEGIN
TL_FN float tlBrdfSpecularNode(uint i) { return kBrdfTables.specular[i]; }
TL_FN float tlBrdfAverageNode(uint i) { return kBrdfTables.average[i]; }
TL_END
#else
layout(set = 0, binding = kBindingBrdfTables, std430) readonly buffer BrdfTablesBuffer { BrdfTables brdfTables; };
float tlBrdfSpecularNode(uint i) { return brdfTables.specular[i]; }
float tlBrdfAverageNode(uint i) { return brdfTables.average[i]; }
#endif

TL_BEGIN
TL_CONST float kDielectricF0 = 0.04f;  // glTF: index of refraction 1.5

struct SurfaceParams {
  vec3 diffuse;          // the diffuse layer's albedo: baseColor (1 - metallic)
  vec3 f0;               // Schlick's F0 of the single-scattering lobe: mix(F0_d, baseColor, metallic)
  vec3 f90;              // and its F90: mix(F90_d, 1, metallic)
  vec3 msFresnel;        // F_ms of the multiple-scattering lobe, mixed like the model: mix(F_ms(F0_d, F90_d), F_ms(baseColor, 1), metallic)
  float alpha;           // GGX alpha = roughness^2
  float roughness;       // perceptual roughness, clamped to [kBrdfMinRoughness, 1]: the tables' axis
  float specular;        // 1: the glTF model; 0: no specular layer (Lambert)
  float singleAverage;   // E_avg: the cosine-weighted average of E(mu)
  vec3 layerF0;          // F0_d and F90_d: the dielectric layer's Fresnel
  float layerF90;
  vec3 layerMsFresnel;   // F_ms(F0_d, F90_d): the dielectric layer's multiple-scattering Fresnel
  vec3 layerAverage;     // E_d,avg: the cosine-weighted average of the dielectric layer's specular albedo
  vec3 baseColor;        // what it was made from (tlSurfaceWithRoughness)
  float metallic;
  vec3 transmitted;     // the diffuse layer's share that passes through instead (tlSurfaceTransmitting)
  float transmission;   // and the factor t that made it
  float coat;           // KHR_materials_clearcoat's factor (tlSurfaceCoated; 0: none)
  float coatRoughness;  // its perceptual roughness, clamped as roughness is
  float coatAlpha;      // and its GGX alpha
  float coatSingleAverage;  // E_avg at the coat's roughness
  float coatMsFresnel;      // F_ms of the coat's multiple-scattering lobe (F0 0.04, F90 1)
  float coatAverage;        // c E_coat,avg: the coat's cosine-weighted average albedo
};

// The tables at (cos theta, roughness): vec2(S, B) with E_F0 = F0 S + B, bilinear.
TL_FN vec2 tlSpecularAlbedoSplit(float cosTheta, float roughness) {
  float x = tlBrdfLutCosineCoord(cosTheta), y = tlBrdfLutRoughnessCoord(roughness);
  uint x0 = min(uint(x), kBrdfLutCosines - 2u), y0 = min(uint(y), kBrdfLutRoughness - 2u);
  float fx = x - float(x0), fy = y - float(y0);
  uint i00 = (y0 * kBrdfLutCosines + x0) * 2u, i10 = i00 + 2u * kBrdfLutCosines;
  vec2 t00 = vec2(tlBrdfSpecularNode(i00), tlBrdfSpecularNode(i00 + 1u));
  vec2 t01 = vec2(tlBrdfSpecularNode(i00 + 2u), tlBrdfSpecularNode(i00 + 3u));
  vec2 t10 = vec2(tlBrdfSpecularNode(i10), tlBrdfSpecularNode(i10 + 1u));
  vec2 t11 = vec2(tlBrdfSpecularNode(i10 + 2u), tlBrdfSpecularNode(i10 + 3u));
  return mix(mix(t00, t01, fx), mix(t10, t11, fx), fy);
}

// The cosine-weighted averages of S and B at a roughness (exactly the average of the
// interpolated table: brdf_lut.h).
TL_FN vec2 tlSpecularAverageSplit(float roughness) {
  float y = tlBrdfLutRoughnessCoord(roughness);
  uint y0 = min(uint(y), kBrdfLutRoughness - 2u);
  float fy = y - float(y0);
  vec2 a0 = vec2(tlBrdfAverageNode(2u * y0), tlBrdfAverageNode(2u * y0 + 1u));
  vec2 a1 = vec2(tlBrdfAverageNode(2u * y0 + 2u), tlBrdfAverageNode(2u * y0 + 3u));
  return mix(a0, a1, fy);
}

// Kulla & Conty's Fresnel factor of the multiple-scattering lobe: the light that scatters more
// than once, each bounce losing 1 - F_avg, and leaving with probability E_avg. F_avg is Schlick's
// from F0 to F90: F0 + (F90 - F0) / 21.
TL_FN vec3 tlMultipleScatteringFresnel(vec3 f0, float f90, float singleAverage) {
  vec3 fAvg = f0 + (vec3(f90) - f0) * (1.0f / 21.0f);
  return fAvg * fAvg * singleAverage / (vec3(1.0f) - fAvg * (1.0f - singleAverage));
}

// The surface with the dielectric's Fresnel given (F0_d, F90_d = specular: tlDielectricFresnel).
TL_FN SurfaceParams tlSurfaceSpecular(vec3 baseColor, float roughness, float metallic, vec3 dielectricF0, float specular) {
  SurfaceParams s;
  float m = clamp(metallic, 0.0f, 1.0f);
  float w = clamp(specular, 0.0f, 1.0f);
  vec3 d0 = clamp(dielectricF0, vec3(0.0f), vec3(w));
  s.baseColor = baseColor;
  s.metallic = m;
  s.roughness = clamp(roughness, kBrdfMinRoughness, 1.0f);
  s.alpha = s.roughness * s.roughness;
  s.diffuse = baseColor * (1.0f - m);
  s.layerF0 = d0;
  s.layerF90 = w;
  s.f0 = mix(d0, baseColor, m);
  s.f90 = mix(vec3(w), vec3(1.0f), m);
  s.specular = 1.0f;
  vec2 average = tlSpecularAverageSplit(s.roughness);
  s.singleAverage = average.x + average.y;
  s.layerMsFresnel = tlMultipleScatteringFresnel(d0, w, s.singleAverage);
  s.msFresnel = mix(s.layerMsFresnel, tlMultipleScatteringFresnel(baseColor, 1.0f, s.singleAverage), m);
  s.layerAverage = d0 * average.x + vec3(w * average.y) + s.layerMsFresnel * (1.0f - s.singleAverage);
  s.transmitted = vec3(0.0f);
  s.transmission = 0.0f;
  s.coat = 0.0f;
  s.coatRoughness = 1.0f;
  s.coatAlpha = 1.0f;
  s.coatSingleAverage = 0.0f;
  s.coatMsFresnel = 0.0f;
  s.coatAverage = 0.0f;
  return s;
}

// KHR_materials_clearcoat: a clear dielectric coat (F0 0.04, F90 1: ior 1.5) of factor c and its
// own roughness over the whole surface, by albedo scaling:
//   f = c f_coat + (1 - c E_coat(mu_o)) f_base,
// E_coat the coat's directional albedo at the view, from the tables that define its lobe. What
// the base reflects or passes is scaled by what the coat lets through, so a white coated surface
// still reflects everything, exactly. The scaling is on the view's side only, as in Autodesk's
// Standard Surface: not reciprocal, which the reference (tracing from the camera) does not need.
// The coat has the surface's shading normal (glTF's clearcoatNormalTexture is not read).
TL_FN SurfaceParams tlSurfaceCoated(SurfaceParams s, float coat, float coatRoughness) {
  s.coat = clamp(coat, 0.0f, 1.0f);
  s.coatRoughness = clamp(coatRoughness, kBrdfMinRoughness, 1.0f);
  s.coatAlpha = s.coatRoughness * s.coatRoughness;
  vec2 average = tlSpecularAverageSplit(s.coatRoughness);
  s.coatSingleAverage = average.x + average.y;
  s.coatMsFresnel = tlMultipleScatteringFresnel(vec3(kDielectricF0), 1.0f, s.coatSingleAverage).x;
  s.coatAverage = s.coat * (kDielectricF0 * average.x + average.y + s.coatMsFresnel * (1.0f - s.coatSingleAverage));
  return s;
}

// c E_coat(mu): the share of the light arriving at cos theta = mu that the coat reflects.
TL_FN float tlCoatAlbedo(SurfaceParams s, float mu) {
  if (!(s.coat > 0.0f)) return 0.0f;
  vec2 split = tlSpecularAlbedoSplit(max(mu, kBrdfMinCosine), s.coatRoughness);
  return s.coat * (kDielectricF0 * split.x + split.y + s.coatMsFresnel * (1.0f - split.x - split.y));
}

// KHR_materials_transmission: a share t of the dielectric's diffuse layer passes through the
// surface instead of scattering back. The layer keeps 1 - t of its albedo and the rest leaves on
// the far side (tlThinTransmittance): what the specular layer does not reflect, tinted by the
// base colour, so reflection plus transmission is the opaque surface's albedo and a white pane
// conserves energy exactly. Metal transmits nothing (its share is baseColor (1 - metallic) t).
TL_FN SurfaceParams tlSurfaceTransmitting(SurfaceParams s, float transmission) {
  float t = clamp(transmission, 0.0f, 1.0f);
  s.transmission = t;
  s.transmitted = s.diffuse * t;
  s.diffuse = s.diffuse * (1.0f - t);
  return s;
}

// glTF's core model: F0_d = 0.04, F90_d = 1.
TL_FN SurfaceParams tlSurface(vec3 baseColor, float roughness, float metallic) {
  return tlSurfaceSpecular(baseColor, roughness, metallic, vec3(kDielectricF0), 1.0f);
}

// No specular layer: f = albedo / pi (the diffuse and clay override modes).
TL_FN SurfaceParams tlLambertSurface(vec3 albedo) {
  SurfaceParams s = tlSurfaceSpecular(albedo, 1.0f, 0.0f, vec3(0.0f), 0.0f);
  s.specular = 0.0f;
  return s;
}

// The same surface at another roughness (the SH specular's directional part, shared/sh_specular.h).
TL_FN SurfaceParams tlSurfaceWithRoughness(SurfaceParams s, float roughness) {
  if (s.specular == 0.0f) return s;  // Lambert does not depend on roughness
  SurfaceParams r = tlSurfaceTransmitting(tlSurfaceSpecular(s.baseColor, roughness, s.metallic, s.layerF0, s.layerF90),
                                          s.transmission);
  return tlSurfaceCoated(r, s.coat, s.coatRoughness);
}

// E(mu) with F = 1, from the split.
TL_FN float tlSingleScatteringAlbedo(vec2 split) { return split.x + split.y; }

// 1 - E_d,avg, the diffuse layer's normaliser: a dielectric of F0 = F90 = 1 (an ior of 0, a
// bright specular colour) reflects everything specularly and leaves the diffuse layer nothing
// (its 1 - E_d(mu) terms are 0 too), so the floor only keeps that 0 from becoming 0 / 0.
TL_FN vec3 tlDiffuseLayerWeight(SurfaceParams s) { return max(vec3(1.0f) - s.layerAverage, vec3(1e-6f)); }

// The dielectric layer's specular albedo E_d(mu) (0 without a specular layer).
TL_FN vec3 tlLayerAlbedo(SurfaceParams s, vec2 split) {
  float e = split.x + split.y;
  return s.specular * (s.layerF0 * split.x + vec3(s.layerF90 * split.y) + s.layerMsFresnel * (1.0f - e));
}

// The light a transmitting surface passes at |cos theta| = mu to the incident direction. A thin
// one passes it straight through, unrefracted, at every roughness (the roughness blurs its
// reflection only): exact for a smooth thin pane, whose parallel faces give the light back its
// direction. The boundary of a volume (KHR_materials_volume) refracts it in the reference
// (reference/path.glsl). The user guide states the approximations.
TL_FN vec3 tlThinTransmittance(SurfaceParams s, float cosTheta) {
  if (!(s.transmission > 0.0f)) return vec3(0.0f);
  vec2 split = tlSpecularAlbedoSplit(max(abs(cosTheta), kBrdfMinCosine), s.roughness);
  return s.transmitted * (vec3(1.0f) - tlLayerAlbedo(s, split)) * (1.0f - tlCoatAlbedo(s, abs(cosTheta)));
}

// One microfacet lobe, f_ss + f_ms, for light from l seen from v (n.l > 0): GGX of perceptual
// roughness `roughness` (alpha = roughness^2) with Schlick's Fresnel from f0 to f90, and
// Kulla & Conty's multiple scattering of Fresnel msFresnel and average albedo singleAverage.
// The base's specular lobes and the coat's are each one.
TL_FN vec3 tlGgxLobe(vec3 n, vec3 v, vec3 l, vec3 f0, vec3 f90, vec3 msFresnel, float roughness, float alpha,
                     float singleAverage) {
  float nl = dot(n, l);
  float nv = max(dot(n, v), kBrdfMinCosine);
  vec3 hv = v + l;
  float hl = length(hv);
  vec3 h = hl > 1e-7f ? hv / hl : n;
  float vh = max(dot(v, h), 0.0f);
  vec3 fresnel = f0 + (f90 - f0) * tlSchlickWeight(vh);
  vec3 single = tlGgxDOfHalfVector(n, h, alpha) * tlSmithVisibility(nl, nv, alpha) * fresnel;
  float eo = tlSingleScatteringAlbedo(tlSpecularAlbedoSplit(nv, roughness));
  float ei = tlSingleScatteringAlbedo(tlSpecularAlbedoSplit(nl, roughness));
  vec3 multiple = msFresnel * ((1.0f - eo) * (1.0f - ei) * kInvPi / max(1.0f - singleAverage, 1e-6f));
  return single + multiple;
}

// The coat's lobe, c f_coat: a clear dielectric's at the coat's roughness.
TL_FN float tlBrdfCoat(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  if (!(dot(n, l) > 0.0f) || !(s.coat > 0.0f)) return 0.0f;
  return s.coat * tlGgxLobe(n, v, l, vec3(kDielectricF0), vec3(1.0f), vec3(s.coatMsFresnel), s.coatRoughness,
                            s.coatAlpha, s.coatSingleAverage)
                      .x;
}

// The specular lobes (f_ss + f_ms) alone, the coat's included.
TL_FN vec3 tlBrdfSpecular(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  if (!(dot(n, l) > 0.0f) || s.specular == 0.0f) return vec3(0.0f);
  vec3 base = tlGgxLobe(n, v, l, s.f0, s.f90, s.msFresnel, s.roughness, s.alpha, s.singleAverage);
  if (!(s.coat > 0.0f)) return base;
  return vec3(tlBrdfCoat(s, n, v, l)) + base * (1.0f - tlCoatAlbedo(s, max(dot(n, v), kBrdfMinCosine)));
}

// The diffuse layer alone.
TL_FN vec3 tlBrdfDiffuse(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  float nl = dot(n, l);
  if (!(nl > 0.0f)) return vec3(0.0f);
  float nv = max(dot(n, v), kBrdfMinCosine);
  vec3 edo = tlLayerAlbedo(s, tlSpecularAlbedoSplit(nv, s.roughness));
  vec3 edi = tlLayerAlbedo(s, tlSpecularAlbedoSplit(nl, s.roughness));
  return s.diffuse * kInvPi * (vec3(1.0f) - edo) * (vec3(1.0f) - edi) / tlDiffuseLayerWeight(s) *
         (1.0f - tlCoatAlbedo(s, nv));
}

// f(l, v) (pi-free: radiance = f E n.l for a light of irradiance E from l); 0 below the surface.
TL_FN vec3 tlBrdf(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  return tlBrdfSpecular(s, n, v, l) + tlBrdfDiffuse(s, n, v, l);
}

// The surface a material override mode shades (shared/material_mode.h): as authored, or Lambert.
TL_FN SurfaceParams tlMaterialSurface(vec3 baseColor, float roughness, float metallic, uint materials) {
  if (materials == kMaterialsAuthored) return tlSurface(baseColor, roughness, metallic);
  return tlLambertSurface(tlMaterialBaseColor(baseColor, materials));
}

// The same with the dielectric's Fresnel (F0_d in rgb, F90_d in w: tlDielectricFresnel).
TL_FN SurfaceParams tlMaterialSurfaceFresnel(vec3 baseColor, float roughness, float metallic, vec4 fresnel, uint materials) {
  if (materials == kMaterialsAuthored) return tlSurfaceSpecular(baseColor, roughness, metallic, vec3(fresnel), fresnel.w);
  return tlLambertSurface(tlMaterialBaseColor(baseColor, materials));
}

// The same with the layers the reference adds: transmission (kept in every mode: a window still
// lets the light in) and the clear coat (a specular layer: the Lambertian modes have none).
TL_FN SurfaceParams tlMaterialSurfaceLayered(vec3 baseColor, float roughness, float metallic, vec4 fresnel,
                                             float transmission, float coat, float coatRoughness, uint materials) {
  SurfaceParams s =
      tlSurfaceTransmitting(tlMaterialSurfaceFresnel(baseColor, roughness, metallic, fresnel, materials), transmission);
  return materials == kMaterialsAuthored ? tlSurfaceCoated(s, coat, coatRoughness) : s;
}

// The surface a G-buffer texel describes (shared/gbuffer.h): gbuffer.baseColor (rgb, and the
// dielectric's F90 in a) and gbuffer.material (r roughness, g metallic, b the dielectric's F0).
TL_FN SurfaceParams tlGbufferSurface(vec4 baseColor, vec4 material, uint materials) {
  vec4 fresnel = vec4(vec3(tlGbufferDecodeF0(material.z)), baseColor.w);
  return tlMaterialSurfaceFresnel(vec3(baseColor), material.x, material.y, fresnel, materials);
}

// Reflected radiance per unit of uniform incident radiance, seen at cos theta = nv: the
// directional albedo of the specular lobes and of the diffuse layer. Exact for this BRDF (the
// compensation is built from the same tables), so a white surface under a uniform sky L shows
// exactly L.
TL_FN vec3 tlEnvironmentSpecular(SurfaceParams s, float nv) {
  vec2 split = tlSpecularAlbedoSplit(max(nv, kBrdfMinCosine), s.roughness);
  float e = tlSingleScatteringAlbedo(split);
  vec3 base = s.specular * (s.f0 * split.x + s.f90 * split.y + s.msFresnel * (1.0f - e));
  float coat = tlCoatAlbedo(s, nv);
  return vec3(coat) + base * (1.0f - coat);
}
TL_FN vec3 tlEnvironmentDiffuse(SurfaceParams s, float nv) {
  return s.diffuse * (vec3(1.0f) - tlLayerAlbedo(s, tlSpecularAlbedoSplit(max(nv, kBrdfMinCosine), s.roughness))) *
         (1.0f - tlCoatAlbedo(s, nv));
}
TL_FN vec3 tlEnvironmentAlbedo(SurfaceParams s, float nv) { return tlEnvironmentSpecular(s, nv) + tlEnvironmentDiffuse(s, nv); }

// The hemispherical (white-sky) albedo: the fraction of uniform incident light the surface
// reflects, averaged over the directions it leaves in; what a surface gives back as a bounce.
TL_FN vec3 tlHemisphericalAlbedo(SurfaceParams s) {
  vec2 average = tlSpecularAverageSplit(s.roughness);
  vec3 specular = s.specular * (s.f0 * average.x + s.f90 * average.y + s.msFresnel * (1.0f - s.singleAverage));
  // A coat scales the base by its average (the view-side scaling averaged over the views).
  float coat = s.coatAverage;
  return vec3(coat) + (specular + s.diffuse * (vec3(1.0f) - s.layerAverage)) * (1.0f - coat);
}

// Ambient occlusion with the occluders' light put back: the fraction 1 - ao of the sky that
// nearby surfaces hide is replaced by their own radiance, taken to be that of a surface of this
// one's hemispherical albedo lit like this one, rho E / pi. Solving E = ao E_open + (1 - ao) rho E
// gives E = E_open * ao / (1 - rho (1 - ao)): the factor returned, per channel (the analytic
// multi-bounce form; Jimenez et al. 2016 fit it to scenes instead). A white surface (rho = 1)
// loses nothing to occlusion: in a white furnace every surface shows the sky's radiance.
TL_FN vec3 tlMultiBounceAo(float ao, vec3 albedo) {
  float a = clamp(ao, 0.0f, 1.0f);
  return vec3(a) / max(vec3(1.0f) - clamp(albedo, vec3(0.0f), vec3(1.0f)) * (1.0f - a), vec3(1e-4f));
}

// Sampling (the reference path tracer): the single-scattering lobe from its visible normals,
// the multiple-scattering lobe and the diffuse layer (both near cosine-shaped) by cosine, each
// chosen in proportion to the albedo it carries at this view (luminance).
TL_FN float tlBrdfSpecularProbability(SurfaceParams s, float nv) {
  vec2 split = tlSpecularAlbedoSplit(max(nv, kBrdfMinCosine), s.roughness);
  float single = s.specular * tlLuminance(s.f0 * split.x + s.f90 * split.y);
  float rest = tlLuminance(s.specular * s.msFresnel * (1.0f - tlSingleScatteringAlbedo(split)) +
                           s.diffuse * (vec3(1.0f) - tlLayerAlbedo(s, split)));
  return single + rest > 0.0f ? single / (single + rest) : 0.0f;
}

// The view the visible normals are drawn for: v, lifted above the surface where a shading
// normal leaves it below (both sampling and its density use this one).
TL_FN vec3 tlSamplingView(vec3 n, vec3 v) {
  float nv = dot(n, v);
  if (nv >= kBrdfMinCosine) return v;
  return normalize(v + (kBrdfMinCosine - nv) * n);
}

// The probability that the reference's path passes a transmitting surface rather than
// reflecting off it: the share of the light at this view that goes through (luminance).
TL_FN float tlTransmissionProbability(SurfaceParams s, float nv) {
  float through = tlLuminance(tlThinTransmittance(s, nv));
  if (!(through > 0.0f)) return 0.0f;
  float back = tlLuminance(tlEnvironmentAlbedo(s, nv));
  return through / (through + back);
}

// The share of tlSampleBrdf's directions drawn from the coat's visible normals: its share of
// the albedo at this view (the rest follow the base's mixture).
TL_FN float tlCoatSamplingProbability(SurfaceParams s, float nv) {
  float coat = tlCoatAlbedo(s, nv);
  if (!(coat > 0.0f)) return 0.0f;
  return clamp(coat / max(tlLuminance(tlEnvironmentAlbedo(s, nv)), 1e-6f), 0.0f, 1.0f);
}

// A reflection of the view about a normal drawn from GGX's visible normals of `alpha`, seen from
// tlSamplingView(n, v); and the solid-angle density of a direction l so drawn. The base's
// single-scattering lobe and the coat's are drawn this way.
TL_FN vec3 tlSampleVisibleReflection(vec3 n, vec3 v, float alpha, vec2 u) {
  vec3 w = tlSamplingView(n, v);
  mat3 basis = tlBasisFromNormal(n);
  vec3 h = basis * tlSampleGgxVisibleNormal(transpose(basis) * w, alpha, u);
  return reflect(-w, h);
}
TL_FN float tlVisibleReflectionPdf(vec3 n, vec3 v, vec3 l, float alpha) {
  vec3 w = tlSamplingView(n, v);
  vec3 h = normalize(w + l);
  float nw = max(dot(n, w), kBrdfMinCosine);
  // Visible normals: D_w(h) = G1(w) max(w.h, 0) D(h) / n.w; reflection: / (4 w.h).
  return dot(w, h) > 0.0f ? tlSmithG1(nw, alpha) * tlGgxDOfHalfVector(n, h, alpha) / (4.0f * nw) : 0.0f;
}

// A direction drawn with the mixture tlBrdfPdf describes; `choice` picks the lobe.
TL_FN vec3 tlSampleBrdf(SurfaceParams s, vec3 n, vec3 v, float specularProbability, vec2 u, float choice) {
  float coatProbability = tlCoatSamplingProbability(s, dot(n, v));
  if (choice < coatProbability) return tlSampleVisibleReflection(n, v, s.coatAlpha, u);
  if (coatProbability > 0.0f) choice = (choice - coatProbability) / (1.0f - coatProbability);
  if (choice < specularProbability) return tlSampleVisibleReflection(n, v, s.alpha, u);
  return tlLocalToWorld(tlSampleCosineHemisphere(u), n);
}

// The solid-angle density of tlSampleBrdf's direction l.
TL_FN float tlBrdfPdf(SurfaceParams s, vec3 n, vec3 v, vec3 l, float specularProbability) {
  float nl = dot(n, l);
  if (!(nl > 0.0f)) return 0.0f;
  float pdf = (1.0f - specularProbability) * nl * kInvPi;
  if (specularProbability > 0.0f) pdf += specularProbability * tlVisibleReflectionPdf(n, v, l, s.alpha);
  float coatProbability = tlCoatSamplingProbability(s, dot(n, v));
  if (!(coatProbability > 0.0f)) return pdf;
  return (1.0f - coatProbability) * pdf + coatProbability * tlVisibleReflectionPdf(n, v, l, s.coatAlpha);
}
TL_END
#endif
