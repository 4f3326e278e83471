// The layout of the shared BRDF's precomputed tables (shared/shading.h), shared by the program
// that makes them (shaders/generator/brdf_tables.cpp, at build time) and the code that reads
// them, so both put the same node at the same place.
//
// The tables are one BrdfTables: the C++ code has it as the constant kBrdfTables, generated at
// build time into <build>/generated/shared/brdf_tables.h; the shaders read the same bytes from
// the buffer the session uploads once (graph resource "brdf.tables", bound at set 0 binding
// kBindingBrdfTables in every pass that shades with shared/shading.h). (A constant array in
// GLSL would be copied into every invocation's private memory wherever it is indexed.)
//   specular[(r * kBrdfLutCosines + c) * 2 + k]
//       the directional albedo of the single-scattering GGX lobe D V F with Schlick's Fresnel,
//       split by linearity in F0 (the split sum): E_F0(mu) = F0 * S + B (k = 0: S, k = 1: B), so
//       E = S + B is the lobe's albedo with F = 1. Node c sits at cos(theta) = (c / (Nc - 1))^2,
//       denser at grazing angles where the albedo changes fastest; node r at perceptual
//       roughness mix(kBrdfMinRoughness, 1, r / (Nr - 1)) (the model's range: the smoothest
//       lobe is a node, not an interpolation towards a roughness it never has).
//   average[r * 2 + k]
//       the cosine-weighted averages 2 int S mu dmu and 2 int B mu dmu of the table's own
//       piecewise-linear interpolant at roughness node r (the Kulla-Conty E_avg is their sum):
//       taken from the interpolant, not from the lobe, so the energy the compensation adds
//       matches to the last bit what the interpolated table says is missing.
#ifndef TL_SHARED_BRDF_LUT_H
#define TL_SHARED_BRDF_LUT_H
#include "common.h"

TL_BEGIN
TL_CONST uint kBrdfLutCosines = 32u;
TL_CONST uint kBrdfLutRoughness = 32u;
// A perfect mirror has no finite GGX lobe; below this roughness the lobe is sharper than any
// pixel or table can resolve.
TL_CONST float kBrdfMinRoughness = 0.045f;
// The smallest cosine the lobe is evaluated at (a view exactly along the surface).
TL_CONST float kBrdfMinCosine = 1e-4f;

TL_CONST uint kBindingBrdfTables = 48u;  // set 0, std430 BrdfTables, read-only

struct BrdfTables {
  float specular[2u * kBrdfLutCosines * kBrdfLutRoughness];
  float average[2u * kBrdfLutRoughness];
};

// Continuous table coordinates: node index plus fraction, in [0, N - 1].
TL_FN float tlBrdfLutCosineCoord(float cosTheta) {
  return sqrt(clamp(cosTheta, 0.0f, 1.0f)) * float(kBrdfLutCosines - 1u);
}
TL_FN float tlBrdfLutRoughnessCoord(float roughness) {
  return (clamp(roughness, kBrdfMinRoughness, 1.0f) - kBrdfMinRoughness) / (1.0f - kBrdfMinRoughness) *
         float(kBrdfLutRoughness - 1u);
}
// Where each node sits (the generator evaluates the lobe there).
TL_FN float tlBrdfLutNodeCosine(uint c) {
  float x = float(c) / float(kBrdfLutCosines - 1u);
  return max(x * x, kBrdfMinCosine);
}
TL_FN float tlBrdfLutNodeRoughness(uint r) {
  return mix(kBrdfMinRoughness, 1.0f, float(r) / float(kBrdfLutRoughness - 1u));
}
TL_END
#ifdef __cplusplus
static_assert(sizeof(tl::shared::BrdfTables) == sizeof(float) * 2 * (32 * 32 + 32));
#endif
#endif
