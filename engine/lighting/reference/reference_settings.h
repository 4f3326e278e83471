// The reference path tracer's settings.
// One line per setting, the columns of TL_RENDER_SETTINGS (render_settings.h), which gathers
// this group and names its owner: `owner` below is that name, so no line restates it.
// A new setting of this group is one line here.
#pragma once

// clang-format off
#define TL_REFERENCE_SETTINGS(X, owner) \
  X(uint32_t, referenceBounces, 64, 1, 64, "events", owner, "reference", kSettingPlain, "scattering events per path (1 = direct light only, 2 = one indirect bounce); Russian roulette ends paths first") \
  X(uint32_t, referenceSamplesPerFrame, 1, 1, 1024, "spp", owner, "", kSettingPlain, "samples per pixel added each frame (render --spp sets it)") \
  X(bool, referenceEmitterSampling, true, 0, 1, "", owner, "reference", kSettingPlain, "emissive triangles drawn by power at every scattering event (next-event estimation, power heuristic against the BRDF's rays); off: found only by rays that hit them") \
  X(uint32_t, referenceAdaptive, 0, 0, 2, "", owner, "reference", kSettingPlain, "where each frame's samples go: 0 every pixel alike; 1 in proportion to each pixel's noise as an independent pilot measures it (unbiased; loses where rare paths carry the noise: docs/design/reference.md); 2 by the estimate's own samples (biased: a diagnostic)") \
  X(bool, referenceRawRayProbe, false, 0, 1, "", owner, "", kSettingNoPanel, "benchmark: also trace a trivial kernel on the reference's top level (reference.rawRays; bench --rays)")
// clang-format on
