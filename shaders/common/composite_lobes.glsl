// The composite's reflected light at a surface pixel, split by the lobe that reflects it: the
// sun (through the shadow map or hybrid shadows' visibility) and the path's indirect diffuse and
// specular. The composite adds the two, the light table and the emission; composite.stages
// writes them apart (compare's per-lobe split), so both come from this one code. The includer
// includes common/path_indirect.glsl and common/sun_shadow.glsl (with its bindings) first.
struct CompositeLobes {
  vec3 diffuse, specular;
  float ao;         // the path's AO (1 where it has none)
  vec3 irradiance;  // the indirect diffuse irradiance, times the material's occlusion
};

// `material`: gbuffer.material (its a is the material's occlusion, which darkens both
// indirect terms, never the sun, the lights or emission).
CompositeLobes compositeLobes(ivec2 p, vec3 position, vec3 n, vec3 v, SurfaceParams s, vec4 material) {
  CompositeLobes l;
  // Indirect diffuse: the diffuse layer's albedo under uniform light from the irradiance's
  // directions (shared/shading.h; exact for a uniform sky), radiance = albedo / pi * E.
  l.ao = pathAmbientOcclusion(p);
  float occlusion = material.w;
  l.irradiance = occlusion * pathDiffuseIrradiance(p, n, position, l.ao, tlHemisphericalAlbedo(s), tlSkyIrradiance(frame, n));
  l.diffuse = tlEnvironmentDiffuse(s, dot(n, v)) * kInvPi * l.irradiance;
  // Indirect specular: from the path's SH where it has one, else the sky's (times AO).
  l.specular = occlusion * pathSpecular(p, n, v, position, l.ao, s, tlSkyRadiance(frame, reflect(-v, n)));
  float nl = dot(n, frame.sunToLight.xyz);
  if (nl > 0.0) {
    vec3 sun = frame.sunIrradiance.rgb * (nl * sunVisibilityShading(position, n, p));
    l.diffuse += sun * tlBrdfDiffuse(s, n, v, frame.sunToLight.xyz);
    l.specular += sun * tlBrdfSpecular(s, n, v, frame.sunToLight.xyz);
  }
  return l;
}
