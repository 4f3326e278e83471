// What the composite takes from a lighting path, as the quantities it multiplies: the
// ambient occlusion, the diffuse irradiance (sky and bounce light; the sun is separate) and
// the indirect specular. Wherever AO darkens light, the occluders' own light is put back for
// the surface's albedo (shared/shading.h tlMultiBounceAo): occlusion hides the sky, not light.
// The composite and the composite.stages pass both include it, so the per-stage buffers
// hold exactly what the final image used. The includer includes shared/gbuffer.h and sh.h
// and declares `push` (CompositePush); the path's images are bound here, at the composite's
// binding numbers, for both.
#include "shared/sh_specular.h"

layout(set = 0, binding = kCompositeAo) uniform sampler2D pathAo;
layout(set = 0, binding = kCompositeShY) uniform sampler2D pathShY;
layout(set = 0, binding = kCompositeCoCg) uniform sampler2D pathCoCg;
layout(set = 0, binding = kCompositeFarShY) uniform sampler2D farShY;
layout(set = 0, binding = kCompositeFarCoCg) uniform sampler2D farCoCg;
layout(set = 0, binding = kCompositeFarAo) uniform sampler2D farAo;
layout(set = 0, binding = kCompositeSpecular) uniform sampler2D tracedSpecular;

// 1 where the path gives no AO.
float pathAmbientOcclusion(ivec2 p) {
  return (push.flags & kCompositeHasAo) != 0u ? clamp(texelFetch(pathAo, p, 0).r, 0.0, 1.0) : 1.0;
}

// The weight of the path's own GI at this position: 1 before the blend distance, falling to
// 0 over the blend width (beyond it the far field, another path's GI, or the sky).
float pathGiFade(vec3 position) {
  return push.giBlendDistance > 0.0
             ? clamp((push.giBlendDistance - length(position)) / max(push.giBlendWidth, 1e-6), 0.0, 1.0)
             : 1.0;
}
ShLumaCoCg pathSh(ivec2 p) { return tlShMake(texelFetch(pathShY, p, 0), texelFetch(pathCoCg, p, 0).xy); }
ShLumaCoCg farSh(ivec2 p) { return tlShMake(texelFetch(farShY, p, 0), texelFetch(farCoCg, p, 0).xy); }
float farAmbientOcclusion(ivec2 p) { return clamp(texelFetch(farAo, p, 0).r, 0.0, 1.0); }

// Without a path's GI: the sky's irradiance on an unoccluded surface (`skyIrradiance`: pi*L for
// the uniform sky, the environment map's SH irradiance, frame.h tlSkyIrradiance), times AO.
// With it: the path's irradiance resolved against the normal (it already holds the sky's
// occlusion, so AO is not applied twice unless the path asks), fading beyond the blend
// distance to the far field (another path's GI) or, without one, to the sky.
vec3 pathDiffuseIrradiance(ivec2 p, vec3 n, vec3 position, float ao, vec3 albedo, vec3 openSkyIrradiance) {
  vec3 occlusion = tlMultiBounceAo(ao, albedo);
  vec3 skyIrradiance = openSkyIrradiance * occlusion;
  if ((push.flags & kCompositeHasGi) == 0u) return skyIrradiance;
  vec3 gi = tlShResolveIrradiance(pathSh(p), n);
  if ((push.flags & kCompositeAoOnGi) != 0u) gi *= occlusion;
  float fade = pathGiFade(position);
  if (fade >= 1.0) return gi;
  vec3 far = skyIrradiance;
  if ((push.flags & kCompositeHasFarGi) != 0u)
    far = tlShResolveIrradiance(farSh(p), n) * tlMultiBounceAo(farAmbientOcclusion(p), albedo);
  return mix(far, gi, fade);
}

// Indirect specular radiance. Without a path's GI (or with kCompositeSpecularGi off): the sky
// (`skyRadiance`: the uniform sky's, or the environment map's band-limited radiance along the
// mirror direction) through the split-sum environment BRDF, times AO. With it: the specular the
// path's SH implies (shared/sh_specular.h: dominant direction, roughness from the
// directionality, GGX), so a metal indoors reflects the room, not the sky; it fades beyond
// the blend distance like the diffuse. Where the path traced reflections (kCompositeHasTracedSpecular,
// shared/rt_specular.h): their lobe-weighted radiance times the specular albedo, blended into
// the estimate above over the seam near the traced roughness threshold.
vec3 pathSpecularFromSh(ivec2 p, vec3 n, vec3 v, vec3 position, float ao, SurfaceParams s, vec3 skyRadiance) {
  vec3 albedo = tlHemisphericalAlbedo(s);
  vec3 occlusion = tlMultiBounceAo(ao, albedo);
  vec3 sky = skyRadiance * tlEnvironmentSpecular(s, dot(n, v)) * occlusion;
  if ((push.flags & kCompositeHasGi) == 0u || (push.flags & kCompositeSpecularGi) == 0u) return sky;
  vec3 specular = tlShSpecular(pathSh(p), s, n, v, push.openSkyDirectionality);
  if ((push.flags & kCompositeAoOnGi) != 0u) specular *= occlusion;
  float fade = pathGiFade(position);
  if (fade >= 1.0) return specular;
  vec3 far = sky;
  if ((push.flags & kCompositeHasFarGi) != 0u)
    far = tlShSpecular(farSh(p), s, n, v, push.farOpenSkyDirectionality) * tlMultiBounceAo(farAmbientOcclusion(p), albedo);
  return mix(far, specular, fade);
}
vec3 pathSpecular(ivec2 p, vec3 n, vec3 v, vec3 position, float ao, SurfaceParams s, vec3 skyRadiance) {
  vec4 traced = (push.flags & kCompositeHasTracedSpecular) != 0u ? texelFetch(tracedSpecular, p, 0) : vec4(0.0);
  if (!(traced.a > 0.0)) return pathSpecularFromSh(p, n, v, position, ao, s, skyRadiance);
  vec3 fromRays = tlEnvironmentSpecular(s, dot(n, v)) * traced.rgb;
  if (traced.a >= 1.0) return fromRays;
  return mix(pathSpecularFromSh(p, n, v, position, ao, s, skyRadiance), fromRays, traced.a);
}
