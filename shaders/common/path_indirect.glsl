// What the composite takes from a lighting path, as the quantities it multiplies: the
// ambient occlusion and the diffuse irradiance (sky and bounce light; the sun is separate).
// The composite and the composite.stages pass both include it, so the per-stage buffers
// hold exactly what the final image used. The includer includes shared/gbuffer.h and sh.h
// and declares `push` (CompositePush); the path's images are bound here, at the composite's
// binding numbers, for both.

layout(set = 0, binding = kCompositeAo) uniform sampler2D pathAo;
layout(set = 0, binding = kCompositeShY) uniform sampler2D pathShY;
layout(set = 0, binding = kCompositeCoCg) uniform sampler2D pathCoCg;
layout(set = 0, binding = kCompositeFarShY) uniform sampler2D farShY;
layout(set = 0, binding = kCompositeFarCoCg) uniform sampler2D farCoCg;
layout(set = 0, binding = kCompositeFarAo) uniform sampler2D farAo;

// 1 where the path gives no AO.
float pathAmbientOcclusion(ivec2 p) {
  return (push.flags & kCompositeHasAo) != 0u ? clamp(texelFetch(pathAo, p, 0).r, 0.0, 1.0) : 1.0;
}

// Without a path's GI: the uniform sky, irradiance pi*L on an unoccluded surface, times AO.
// With it: the path's irradiance resolved against the normal (it already holds the sky's
// occlusion, so AO is not applied twice unless the path asks), fading beyond the blend
// distance to the far field (another path's GI) or, without one, to the sky.
vec3 pathDiffuseIrradiance(ivec2 p, vec3 n, vec3 position, float ao, vec3 skyRadiance) {
  vec3 skyIrradiance = kPi * skyRadiance * ao;
  if ((push.flags & kCompositeHasGi) == 0u) return skyIrradiance;
  ShLumaCoCg sh = tlShMake(texelFetch(pathShY, p, 0), texelFetch(pathCoCg, p, 0).xy);
  vec3 gi = tlShResolveIrradiance(sh, n);
  float fade = push.giBlendDistance > 0.0
                   ? clamp((push.giBlendDistance - length(position)) / max(push.giBlendWidth, 1e-6), 0.0, 1.0)
                   : 1.0;
  if ((push.flags & kCompositeAoOnGi) != 0u) gi *= ao;
  if (fade >= 1.0) return gi;
  // Beyond the blend distance: the far field's GI (with its own AO), else the sky.
  vec3 far = skyIrradiance;
  if ((push.flags & kCompositeHasFarGi) != 0u) {
    ShLumaCoCg farSh = tlShMake(texelFetch(farShY, p, 0), texelFetch(farCoCg, p, 0).xy);
    far = tlShResolveIrradiance(farSh, n) * clamp(texelFetch(farAo, p, 0).r, 0.0, 1.0);
  }
  return mix(far, gi, fade);
}
