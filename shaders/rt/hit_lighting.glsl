// The light a GI ray brings back from its hit, shared by hit lighting (rt/lighting.rgen) and the
// disocclusion rays (rt/disocclusion.rgen) so both shade a hit the same way: last frame's
// shaded radiance where the hit was on screen (Metro: "lighting already computed in a deferred
// way? use it"), re-coloured to the hit's albedo; else the sun through a shadow ray, the sky
// through one cosine-distributed ray (RtPush::hitSky) and the hit's emission. Include after
// rt/rt_common.glsl. The shadow miss shader is miss index 0 of
// every pipeline that includes this.
layout(set = 0, binding = kRtBindingTlas) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = kRtBindingHistRadiance) uniform sampler2D previousRadiance;
layout(set = 0, binding = kRtBindingHistDepth) uniform sampler2D previousViewDepth;
layout(set = 0, binding = kRtBindingBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtBindingEmissive) uniform sampler2D gEmissive;

layout(location = 1) rayPayloadEXT float visible;

// Last frame's shaded pixel at the hit, if the hit was on screen there (same depth).
bool screenRadianceAt(vec3 hitPosition, uint hit, out vec3 radiance) {
  vec4 clip = frame.prevViewProj * vec4(hitPosition, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
  ivec2 q = ivec2(uv * frame.viewport.xy);
  float w = texelFetch(previousViewDepth, q, 0).r;
  if (w <= 0.0 || abs(w - clip.w) > 0.03 * clip.w) return false;
  // This frame's G-buffer at last frame's pixel: the albedo it was shaded with.
  vec3 screenAlbedo = tlRtHitAlbedoFromMaterial(texelFetch(gBaseColor, q, 0).rgb, texelFetch(gMaterial, q, 0).g);
  radiance = tlRtRecolourScreenRadiance(texelFetch(previousRadiance, q, 0).rgb, texelFetch(gEmissive, q, 0).rgb,
                                        screenAlbedo, tlRtHitAlbedo(hit));
  return true;
}

// Whether a ray from just off the hit escapes the scene (miss shader 0 sets `visible`).
float escapes(vec3 hitPosition, float distance, vec3 normal, vec3 direction) {
  // The stored distance is a half: the rebuilt point may sit up to 2^-11 of the distance off
  // the surface, so the ray leaves by more than that.
  vec3 start = tlOffsetRayOrigin(hitPosition + normal * (distance * (1.0 / 1024.0)), normal);
  visible = 0.0;
  traceRayEXT(tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT,
              0xFF, 0, 0, 0, start, push.tMin, direction, 1e30, 1);
  return visible;
}

// The hit lit afresh: its emission, the sun through a shadow ray and, with hitSky, the sky
// through one ray drawn around the hit's normal by cosine: for a uniform sky L the reflected
// radiance is albedo / pi * (pi L * the escaping share), so one ray's estimate is albedo * L
// when it escapes. `normal` faces the ray; `seed` draws the sky ray's direction.
vec3 freshHitRadiance(vec3 hitPosition, float distance, uint hit, vec3 normal, vec3 emission, uvec3 seed) {
  vec3 radiance = emission;
  vec3 albedo = tlRtHitAlbedo(hit);
  vec3 toSun = frame.sunToLight.xyz;
  float nl = dot(normal, toSun);
  if ((frame.flags & kFrameFlagSunShadows) != 0u && nl > 0.0)
    radiance += albedo * kInvPi * frame.sunIrradiance.rgb * (nl * escapes(hitPosition, distance, normal, toSun));
  if (push.hitSky != 0u && any(greaterThan(frame.skyRadiance.rgb, vec3(0.0)))) {
    vec3 d = tlLocalToWorld(tlSampleCosineHemisphere(tlRandom2(seed)), normal);
    radiance += albedo * frame.skyRadiance.rgb * escapes(hitPosition, distance, normal, d);
  }
  return radiance;
}
