// A surface point lit by the light table (shared/lights.h): every light when there are at most
// kLightsLoopMax, else kLightPicks lights chosen by resampled importance sampling (candidates
// drawn by power, one kept in proportion to its unshadowed contribution here: power and
// distance, cone, cosine), each an unbiased estimate of the sum. The includer includes
// shared/frame.h, lights.h and sampling.h, declares `frame`, and defines before including
//   float lightVisibility(uint light, vec3 toLight, float distance)  1 where light `light` of the
//                                   table is seen from the point (a shadow ray, a shadow map; 1: unshadowed)
//   vec3 lightResponse(vec3 toLight)                      the BRDF times the cosine there
// and the sum is reflected radiance. An includer that sums something else (the I-buffer's
// light sums, common/ibuffer_lights.glsl) defines TL_LIGHTS_CUSTOM_SUM and, instead of
// lightResponse, the type LightSum with lightSumZero(), lightSumAdd(LightSum, LightSum),
// lightSumScale(LightSum, float) and LightSum lightContribution(uint light, LightIncidence li)
// (light `light` of the table, its visibility included).
layout(set = 0, binding = kBindingLights, std430) readonly buffer LightTable { GpuLight lights[]; };

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
  return li.irradiance * response * lightVisibility(light, li.toLight, li.distance);
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
  if (frame.lightCount <= kLightsLoopMax) {
    for (uint i = 0u; i < frame.lightCount; ++i) sum = lightSumAdd(sum, lightContribution(i, tlLightIncidence(lights[i], position)));
    return sum;
  }
  for (uint pick = 0u; pick < kLightPicks; ++pick) {
    float weightSum = 0.0, keptTarget = 0.0;
    LightIncidence kept;
    uint keptIndex = 0u;
    for (uint c = 0u; c < kLightCandidates; ++c) {
      uvec3 h = tlPcg3d(seed + uvec3(0u, 0u, (pick * kLightCandidates + c + 1u) * 0x9E3779B9u));
      uint i = lightPick(tlUintToUnitFloat(h.x));
      LightIncidence li = tlLightIncidence(lights[i], position);
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
