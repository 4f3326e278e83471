// The light a GI ray brings back from its hit, shared by hit lighting (rt/lighting.rgen) and the
// disocclusion rays (rt/disocclusion.rgen) so both shade a hit the same way: last frame's
// shaded radiance where the hit was on screen (Metro: "lighting already computed in a deferred
// way? use it"), re-coloured to the hit's albedo; else the sun through a shadow ray, the sky
// through one cosine-distributed ray (RtPush::hitSky), and the emitters through one sample
// (RtPush::emitterCount) or, without emitter sampling, the hit's own emission, and the light
// table (shared/lights.h) by next-event estimation with shadow rays. Also the pixel's own
// emitter sample (the light table at the pixel is lights.direct's). Include after
// rt/rt_common.glsl. The shadow miss shader is miss index 0 of every pipeline that includes
// this. With the radiance cache on (RtPush::cacheLookup) a hit lit afresh takes the light
// arriving from everything but the sun, the emitters and the light table from its cell
// (shared/rt_cache.h) instead of the sky ray: every bounce, at the price of a lookup.
#include "shared/rt_cache.h"
layout(set = 0, binding = kRtBindingTlas) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = kRtBindingPreviousRadiance) uniform sampler2D previousRadiance;
layout(set = 0, binding = kRtBindingPreviousViewDepth) uniform sampler2D previousViewDepth;
layout(set = 0, binding = kRtBindingBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtBindingEmissive) uniform sampler2D gEmissive;

layout(set = 0, binding = kRtBindingEmitters, std430) readonly buffer Emitters { Emitter emitters[]; };
#include "common/emitter_pick.glsl"
layout(set = 0, binding = kRtBindingCacheEntries, std430) readonly buffer CacheEntries { RtCacheEntry cacheEntries[]; };

layout(location = 1) rayPayloadEXT float visible;

// The light table at a hit lit afresh: a Lambertian surface of the hit's albedo, shadow rays
// from gLightStart (the includes below need them declared first).
vec3 gLightStart, gLightNormal, gLightAlbedo;
float unoccluded(vec3 start, vec3 direction, float tMax);
float lightVisibility(uint light, vec3 toLight, float distance) {
  return unoccluded(gLightStart, toLight, distance >= 1e29 ? 1e30 : distance * (1.0 - 1e-4));
}
vec3 lightResponse(vec3 toLight) { return gLightAlbedo * (kInvPi * max(dot(gLightNormal, toLight), 0.0)); }
#define TL_LIGHTS_AREA TL_AREA_SAMPLED  // area lights: one point on the shape, one shadow ray
#include "common/lights.glsl"

// With emitter sampling on, a ray that finds an emitter leaves its emission out: the emitter
// sample (emitterLight) counts that light instead.
bool emissionFromRays() { return push.emitterCount == 0u; }

// Last frame's shaded pixel at the hit, if the hit was on screen there (same depth).
bool screenRadianceAt(vec3 hitPosition, uint hit, out vec3 radiance) {
  vec4 clip = frame.prevViewProj * vec4(hitPosition, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
  ivec2 q = ivec2(uv * frame.viewport.xy);
  float w = texelFetch(previousViewDepth, q, 0).r;
  float hitW = viewWOfClip(clip);
  if (w <= 0.0 || abs(w - hitW) > 0.03 * hitW) return false;
  // This frame's G-buffer at last frame's pixel: the albedo it was shaded with.
  vec3 screenAlbedo = tlMaterialHitAlbedo(texelFetch(gBaseColor, q, 0).rgb, texelFetch(gMaterial, q, 0).g,
                                          tlFrameMaterials(frame.flags));
  vec3 emission = texelFetch(gEmissive, q, 0).rgb;
  radiance = tlRtRecolourScreenRadiance(texelFetch(previousRadiance, q, 0).rgb, emission, screenAlbedo, tlRtHitAlbedo(hit));
  if (!emissionFromRays()) radiance = max(radiance - emission, vec3(0.0));
  return true;
}

// Whether a ray from `start` escapes the scene within `tMax` (miss shader 0 sets `visible`).
float unoccluded(vec3 start, vec3 direction, float tMax) {
  visible = 0.0;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT,
              0xFF, 0, 0, 0, start, push.tMin, direction, tMax, 1);
  return visible;
}

// One emitter sample (shared/emitters.h) seen from `start` on a surface with `normal`:
// the direction, and the emitted radiance over its pdf through a shadow ray that stops short
// of the emitter (its own, possibly simplified, surface must not hide it). Multiply by the
// cosine for irradiance. Zero without emitters, behind the surface or when hidden.
vec3 emitterLight(vec3 start, vec3 normal, uvec3 seed, out vec3 direction) {
  direction = normal;
  if (push.emitterCount == 0u) return vec3(0.0);
  uvec3 h = tlPcg3d(seed);
  Emitter e = emitters[emitterPick(h.z, push.emitterCount)];
  vec3 toLight = tlEmitterPoint(e, vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y))) - push.cameraWorld.xyz - start;
  float distance2 = dot(toLight, toLight);
  if (distance2 <= 1e-12 * e.edge1.w) return vec3(0.0);  // on the emitter itself (a share of its area)
  float distance = sqrt(distance2);
  direction = toLight / distance;
  // Beyond the ray length the top level may have culled what lies between (and the rays, which
  // stop there, would not find it either).
  if (dot(normal, direction) <= 0.0 || distance > push.tMax) return vec3(0.0);
  vec3 lightNormal = cross(e.edge1.xyz, e.edge2.xyz);
  float cosLight = dot(lightNormal, direction) / max(length(lightNormal), 1e-30);
  if (cosLight == 0.0) return vec3(0.0);
  float reach = distance * (1.0 - 1e-3) - push.tMin;
  if (reach <= push.tMin) return vec3(0.0);
  return e.radiance.rgb * tlEmitterInversePdf(e, distance2, cosLight) * unoccluded(start, direction, reach);
}

// The radiance cache's C in one cell: false where it holds no sample.
bool cachedCell(uvec2 cell, out vec3 incoming) {
  incoming = vec3(0.0);
  for (uint k = 0u; k < kRtCacheProbes; ++k) {
    RtCacheEntry e = cacheEntries[(cell.x + k) & push.cacheEntryMask];
    if (e.key != cell.y) continue;  // holes left by dropped cells: probe on
    if (e.radiance.w <= 0.0) return false;
    incoming = e.radiance.rgb;
    return true;
  }
  return false;
}

// The radiance cache's C at a camera-relative position with `normal`: its cell's, else its
// coarse cell's (shared/rt_cache.h); false where neither holds a sample (or the cache is off).
bool cachedIncoming(vec3 position, vec3 normal, out vec3 incoming) {
  incoming = vec3(0.0);
  if (push.cacheLookup == 0u) return false;
  vec3 world = position + push.cameraWorld.xyz;
  float distance = length(position);
  if (cachedCell(tlRtCacheCell(world, normal, distance, push.cacheCellSize, push.cacheCellAngle), incoming)) return true;
  return cachedCell(tlRtCacheCoarseCell(world, normal, distance, push.cacheCellSize, push.cacheCellAngle), incoming);
}

// A GI ray that met nothing while its length (RtPush::tMax, shorter than the way out of the
// scene) ran out has not left the scene: what lies beyond it is unknown, never the sky. The
// light arriving at its start from every direction, the radiance cache's C at the surface it
// left, stands in for what it would have brought back (C leaves out what is sampled
// explicitly, as the ray does); without a cell, nothing (the rays that end so turn the cache on).
bool rayEndedInScene(vec3 origin, vec3 dir) { return push.tMax < tlSceneExitDistance(frame, origin, dir); }
vec3 endedRayRadiance(vec3 position, vec3 normal) {
  vec3 incoming;
  return cachedIncoming(position, normal, incoming) ? incoming : vec3(0.0);
}

// Where rays leave a hit rebuilt from its stored distance: the stored distance is a half, so
// the rebuilt point may sit up to 2^-11 of the distance off the surface; rays leave by more.
vec3 hitRayStart(vec3 hitPosition, float distance, vec3 normal) {
  return tlOffsetRayOrigin(hitPosition + normal * (distance * (1.0 / 1024.0)), normal, frame.sceneScale);
}

// The light a hit sends back of what is sampled explicitly there: its emission (when the rays
// count it), the sun through a shadow ray, the emitters through one sample (when on).
// `normal` faces the ray; `seed` draws the emitter sample.
vec3 directHitRadiance(vec3 start, vec3 albedo, vec3 normal, vec3 emission, uvec3 seed) {
  vec3 radiance = emissionFromRays() ? emission : vec3(0.0);
  vec3 toSun = frame.sunToLight.xyz;
  float nl = dot(normal, toSun);
  if ((frame.flags & kFrameFlagSunShadows) != 0u && nl > 0.0)
    radiance += albedo * kInvPi * frame.sunIrradiance.rgb * (nl * unoccluded(start, toSun, 1e30));
  if (push.emitterCount > 0u) {
    vec3 d;
    vec3 light = emitterLight(start, normal, seed + uvec3(0u, 0u, 0x9E3779B9u), d);
    radiance += albedo * kInvPi * light * max(dot(normal, d), 0.0);
  }
  if (frame.lightCount > 0u) {
    gLightStart = start;
    gLightNormal = normal;
    gLightAlbedo = albedo;
    radiance += shadeLights(start, normal, seed + uvec3(0u, 0x6A09E667u, 0u));
  }
  return radiance;
}

// The rest of the light arriving at a hit, as the mean over its cosine lobe (reflected as
// albedo times it): the cache's cell where it has one, else with hitSky the sky through one
// ray drawn around the normal by cosine (for a uniform sky L the reflected radiance is
// albedo / pi * (pi L * the escaping share), so one ray's estimate is albedo * L when it
// escapes), else nothing.
vec3 hitIncoming(vec3 hitPosition, vec3 start, vec3 normal, uvec3 seed) {
  vec3 incoming;
  if (cachedIncoming(hitPosition, normal, incoming)) return incoming;
  if (push.hitSky != 0u && ((frame.flags & kFrameFlagEnvironment) != 0u || any(greaterThan(frame.skyRadiance.rgb, vec3(0.0))))) {
    vec3 d = tlLocalToWorld(tlSampleCosineHemisphere(tlRandom2(seed)), normal);
    // With an environment map, its band-limited radiance along the ray (frame.h tlSkyRadiance).
    return tlSkyRadiance(frame, d) * unoccluded(start, d, 1e30);
  }
  return vec3(0.0);
}

// The hit lit afresh: its direct light plus albedo times what arrives otherwise.
vec3 freshHitRadiance(vec3 hitPosition, float distance, uint hit, vec3 normal, vec3 emission, uvec3 seed) {
  vec3 albedo = tlRtHitAlbedo(hit);
  vec3 start = hitRayStart(hitPosition, distance, normal);
  return directHitRadiance(start, albedo, normal, emission, seed) + albedo * hitIncoming(hitPosition, start, normal, seed);
}

// The pixel's own emitter sample as an SH sample that resolves to its irradiance.
ShLumaCoCg emitterSampleSh(vec3 start, vec3 normal, uvec3 seed) {
  vec3 d;
  vec3 light = emitterLight(start, normal, seed, d);
  if (all(equal(light, vec3(0.0)))) return tlShZero();
  return tlShScale(tlShProjectRadiance(d, light), tlRtShWeightForPdf(dot(normal, d), 1.0));
}
