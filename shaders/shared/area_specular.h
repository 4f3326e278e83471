// The glossy reflection of an area light in the rasterising paths' pixels (direct, legacy and
// rt's lights.direct). Their analytic term (shared/area_lights.h tlAreaLightAnalytic) is exact
// for the diffuse layer, but a glossy lobe evaluated in the one direction of the vector
// irradiance sees the shape as a point light of its power: 14x too bright at roughness 0.15 and
// 2.3x at 0.3 at the highlight's centre, and far too dark where a large shape fills the lobe
// away from its mean direction. The specular lobes are therefore estimated as the reference
// estimates them: one point drawn on the shape and one direction drawn from the lobe (the GGX
// visible normals), each weighted against the other's density by the power heuristic (Veach
// 1995): unbiased for any shape, size and roughness (the narrow lobes' light comes from the
// lobe's own samples, the wide ones' from the shape's), noisy, and accumulated over frames by
// lights.direct while nothing moves (lighting/common/lights_pass.cpp). Unshadowed, like the
// analytic term: the shadow (a map's lookup, or shadow rays) scales the whole light.
// Included after shared/lights.h and shared/shading.h; compiled as C++ too (tests/unit).
#ifndef TL_SHARED_AREA_SPECULAR_H
#define TL_SHARED_AREA_SPECULAR_H

TL_BEGIN

// The solid-angle density of a direction l from the specular lobe's visible normals alone.
TL_FN float tlSpecularLobePdf(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
  return tlVisibleReflectionPdf(n, v, l, s.alpha);
}

// The two weighted samples of one estimate: directions towards the shape and their weights as
// irradiance on the surface (E n.l, multiple-importance weight included): the lobes' radiance is
// sum f_spec(l_k) weight_k. A weight of 0 is a sample that missed. The redeferred form adds the
// same samples to the I-buffer's specular sums (common/ibuffer_lights.glsl), so both forms agree.
struct AreaSpecularSamples {
  vec3 towardsShape, shapeWeight;  // a point drawn on the shape
  vec3 alongLobe, lobeWeight;      // a direction drawn from the lobe that meets the shape
};

// uLight draws the shape's point, uLobe the lobe's direction. Only the roughness and whether
// there is a specular layer matter (no colour): the I-buffer's geometry surface serves too.
TL_FN AreaSpecularSamples tlAreaLightSpecularSamples(GpuLight light, SurfaceParams s, vec3 n, vec3 v, vec3 position, vec2 uLight, vec2 uLobe) {
  AreaSpecularSamples r;
  r.towardsShape = n;
  r.alongLobe = n;
  r.shapeWeight = vec3(0.0f);
  r.lobeWeight = vec3(0.0f);
  if (s.specular == 0.0f) return r;  // Lambert: no lobe
  LightIncidence ls = tlAreaLightSample(light, position, uLight);
  float nl = dot(n, ls.toLight);
  if (ls.pdf > 0.0f && nl > 0.0f) {
    r.towardsShape = ls.toLight;
    r.shapeWeight = ls.irradiance * (nl * tlPowerHeuristic(ls.pdf, tlSpecularLobePdf(s, n, v, ls.toLight)));
  }
  vec3 l = tlSampleVisibleReflection(n, v, s.alpha, uLobe);
  nl = dot(n, l);
  if (nl > 0.0f) {
    AreaHit hit = tlAreaLightHit(light, position, l);
    float pdf = tlSpecularLobePdf(s, n, v, l);
    if (hit.t > 0.0f && pdf > 0.0f) {
      r.alongLobe = l;
      r.lobeWeight = vec3(light.intensity) * (nl / pdf * tlPowerHeuristic(pdf, hit.pdf));
    }
  }
  return r;
}

// One estimate of the light the specular lobes reflect from the area light (radiance, before
// visibility).
TL_FN vec3 tlAreaLightSpecular(GpuLight light, SurfaceParams s, vec3 n, vec3 v, vec3 position, vec2 uLight, vec2 uLobe) {
  AreaSpecularSamples r = tlAreaLightSpecularSamples(light, s, n, v, position, uLight, uLobe);
  return r.shapeWeight * tlBrdfSpecular(s, n, v, r.towardsShape) + r.lobeWeight * tlBrdfSpecular(s, n, v, r.alongLobe);
}

TL_END

#endif
