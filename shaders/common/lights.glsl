// A surface point lit by the light table (shared/lights.h): every light when there are at most
// kLightsLoopMax, else kLightPicks lights chosen by resampled importance sampling (candidates
// drawn by power, one kept in proportion to its unshadowed contribution here: power and
// distance, cone, cosine), each an unbiased estimate of the sum. The includer includes
// shared/frame.h, lights.h and sampling.h, declares `frame`, and defines before including
//   float lightVisibility(uint light, vec3 toLight, float distance)  1 where light `light` of the
//                                   table is seen from the point (a shadow ray, a shadow map; 1: unshadowed)
//   vec3 lightResponse(vec3 toLight)                      the BRDF times the cosine there
// and the sum is reflected radiance. One that defines TL_LIGHTS_TINTED also defines vec3
// lightTint(), the colour of what its last lightVisibility let through over that visibility.
// An includer that sums something else (the I-buffer's light sums, common/ibuffer_lights.glsl) defines TL_LIGHTS_CUSTOM_SUM and, instead of
// lightResponse, the type LightSum with lightSumZero(), lightSumAdd(LightSum, LightSum),
// lightSumScale(LightSum, float) and LightSum lightContribution(uint light, LightIncidence li)
// (light `light` of the table, its visibility included, through lightVisibilityOf).
//
// Area lights (shared/area_lights.h), by what the includer defines TL_LIGHTS_AREA as:
//   TL_AREA_ANALYTIC (default)  the whole shape's unshadowed light (tlAreaLightAnalytic), times
//                               lightVisibility towards it (1 for an area light: no shadow map)
//   TL_AREA_ANALYTIC_TRACED     the same times the fraction of kAreaShadowRays shadow rays to
//                               points drawn on the shape (2x2 strata) that arrive: exact where
//                               the light is wholly seen or hidden, noisy only in penumbrae
//   TL_AREA_SAMPLED             next-event estimation: one point drawn on the shape per light
//                               (solid-angle pdf) and one shadow ray to it; with
//                               TL_LIGHTS_AREA_MIS the includer also defines
//                               float lightMisWeight(vec3 toLight, float lightPdf) and counts the
//                               BRDF's rays that meet a light itself (reference/path.glsl)
layout(set = 0, binding = kBindingLights, std430) readonly buffer LightTable { GpuLight lights[]; };

#define TL_AREA_ANALYTIC 0
#define TL_AREA_ANALYTIC_TRACED 1
#define TL_AREA_SAMPLED 2
#ifndef TL_LIGHTS_AREA
#define TL_LIGHTS_AREA TL_AREA_ANALYTIC
#endif
const uint kAreaShadowRays = 4u;

vec3 gLightsAt;     // the point shadeLights shades
vec3 gLightsNormal; // its normal
uvec3 gLightsSeed;  // its seed

// Light `i`'s incidence at `position`; `salt` tells apart the draws at one point.
LightIncidence lightIncidence(uint i, vec3 position, uint salt) {
#if TL_LIGHTS_AREA == TL_AREA_SAMPLED
  if (tlIsAreaLight(lights[i].type)) {
    uvec3 h = tlPcg3d(gLightsSeed + uvec3(salt * 0x85EBCA6Bu, i * 0xC2B2AE35u + 1u, 0x27D4EB2Fu));
    return tlAreaLightSample(lights[i], position, vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y)));
  }
#endif
  return tlLightIncidence(lights[i], position);
}

// The share of light `light` that reaches the point (li: its incidence there).
float lightVisibilityOf(uint light, LightIncidence li) {
#if TL_LIGHTS_AREA == TL_AREA_ANALYTIC_TRACED
  if (tlIsAreaLight(lights[light].type)) {
    // Each ray weighs the irradiance its point of the shape sends (L cos cos / d^2, the sample's
    // estimate times the receiver's cosine): the visible share of the light, not of the shape's
    // area, which a penumbra's near side (more light) and far side (less) would split wrongly.
    float seen = 0.0, drawn = 0.0;
    for (uint k = 0u; k < kAreaShadowRays; ++k) {
      uvec3 h = tlPcg3d(gLightsSeed + uvec3(k * 0x9E3779B9u + 7u, light * 0xC2B2AE35u, 0x165667B1u));
      vec2 u = (vec2(float(k & 1u), float(k >> 1u)) + vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y))) * 0.5;
      LightIncidence s = tlAreaLightSample(lights[light], gLightsAt, u);
      float weight = (s.irradiance.r + s.irradiance.g + s.irradiance.b) * max(dot(gLightsNormal, s.toLight), 0.0);
      if (!(s.pdf > 0.0) || !(weight > 0.0)) continue;
      seen += weight * lightVisibility(light, s.toLight, s.distance);
      drawn += weight;
    }
    return drawn > 0.0 ? seen / drawn : 1.0;
  }
#endif
  return lightVisibility(light, li.toLight, li.distance);
}

// The weight of a sampled area light's estimate against the BRDF's rays that meet it.
float lightSampleWeight(LightIncidence li) {
#if TL_LIGHTS_AREA == TL_AREA_SAMPLED && defined(TL_LIGHTS_AREA_MIS)
  // With more lights than the loop takes, the BRDF's rays count no light (the picks' density is
  // not known there), so the light's estimate keeps all its weight.
  if (li.pdf > 0.0 && frame.lightCount <= kLightsLoopMax) return lightMisWeight(li.toLight, li.pdf);
#endif
  return 1.0;
}

// The draws of an area light's glossy estimate at the point shadeLights shades (xy: the point on
// the shape, zw: the lobe's direction; shared/area_specular.h): the same for the deferred and the
// redeferred forms, so the I-buffer rebuilds the deferred form's radiance. Successive frames
// (gLightsSeed.z) walk an R2 sequence from a shift drawn per pixel and light, so the frames a
// still image accumulates spread over the shape and the lobe rather than clump.
vec4 areaGlossyDraws(uint light) {
  uvec3 h = tlPcg3d(uvec3(gLightsSeed.xy, light * 0x632BE5ABu + 3u)), h2 = tlPcg3d(h);
  return vec4(tlR2Point(gLightsSeed.z, h.xy), tlR2Point(gLightsSeed.z, h2.xy));
}

#ifndef TL_LIGHTS_CUSTOM_SUM
#define LightSum vec3
vec3 lightSumZero() { return vec3(0.0); }
vec3 lightSumAdd(vec3 a, vec3 b) { return a + b; }
vec3 lightSumScale(vec3 a, float k) { return a * k; }

// Reflected radiance from one light, with its visibility (no shadow ray for a light that
// cannot contribute).
vec3 lightContribution(uint light, LightIncidence li) {
  if (all(equal(li.irradiance, vec3(0.0)))) return vec3(0.0);
  vec3 response = lightResponse(li.toLight);
  if (all(equal(response, vec3(0.0)))) return vec3(0.0);
  float visibility = lightVisibilityOf(light, li);
#ifdef TL_LIGHTS_TINTED
  // The includer's shadow rays pass coloured surfaces: visibility is the largest channel of what
  // came through, lightTint() that colour over it (the reference's glass, reference/path.glsl).
  response *= lightTint();
#endif
  return li.irradiance * response * (visibility * lightSampleWeight(li));
}
#endif

// The light whose cumulative selection probability first exceeds u.
uint lightPick(float u) {
  uint lo = 0u, hi = frame.lightCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (u < lights[mid].direction.w) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

// The light table's reflected radiance at `position` (normal n: for resampling only); `seed`
// draws the picks when there are many lights.
LightSum shadeLights(vec3 position, vec3 n, uvec3 seed) {
  LightSum sum = lightSumZero();
  gLightsAt = position;
  gLightsNormal = n;
  gLightsSeed = seed;
  if (frame.lightCount <= kLightsLoopMax) {
    for (uint i = 0u; i < frame.lightCount; ++i) sum = lightSumAdd(sum, lightContribution(i, lightIncidence(i, position, 0u)));
    return sum;
  }
  for (uint pick = 0u; pick < kLightPicks; ++pick) {
    float weightSum = 0.0, keptTarget = 0.0;
    LightIncidence kept;
    uint keptIndex = 0u;
    for (uint c = 0u; c < kLightCandidates; ++c) {
      uvec3 h = tlPcg3d(seed + uvec3(0u, 0u, (pick * kLightCandidates + c + 1u) * 0x9E3779B9u));
      uint i = lightPick(tlUintToUnitFloat(h.x));
      LightIncidence li = lightIncidence(i, position, pick * kLightCandidates + c + 1u);
      float target = tlLightTarget(li, n);
      float weight = target / max(lights[i].intensity.w, 1e-30);
      weightSum += weight;
      if (weight > 0.0 && tlUintToUnitFloat(h.y) * weightSum < weight) {
        kept = li;
        keptIndex = i;
        keptTarget = target;
      }
    }
    // Resampled importance sampling: f(y) / target(y) * (the weights' sum) / candidates.
    if (keptTarget > 0.0)
      sum = lightSumAdd(sum, lightSumScale(lightContribution(keptIndex, kept), weightSum / (float(kLightCandidates) * keptTarget)));
  }
  return lightSumScale(sum, 1.0 / float(kLightPicks));
}
