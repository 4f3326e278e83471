// The reference path tracer's paths, shared by its ray-generation shaders (trace.rgen:
// radiance and AO seen by the camera; irradiance.rgen: the diffuse irradiance at the camera's
// primary hit). The includer declares `frame`, `tlas` and `push` (RefPush) and includes
// shared/frame.h, lights.h, reference.h, ray_origin.h, sampling.h and shading.h.
#include "reference/hit_vertices.glsl"
#include "common/emitter_pick.glsl"

layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };

layout(location = 0) rayPayloadEXT RefHit hit;
layout(location = 1) rayPayloadEXT RefShadowRay shadowRay;

// Deterministic per pixel, per sample and per dimension: the same image for the same spp.
// The dimension has its own 16 bits (beside the pixel's x), so however long a path gets its
// numbers never repeat another sample's.
uvec2 gPixel;
uint gSample;
uint gDimension;
uvec3 nextHash() {
  return tlPcg3d(uvec3(gPixel.x | (gDimension++ << 16u), gPixel.y, gSample ^ (push.seed * 0x9E3779B9u)));
}
vec2 next2() {
  uvec3 h = nextHash();
  return vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y));
}

// Light a path gathers, by its depth: the scattering events between the light and the camera
// (the sky or an emitter seen directly: 0; the sun or the sky on a surface the camera sees: 1;
// light off one other surface first: 2; ...), what --bounces caps. An includer that defines
// TL_REFERENCE_DEPTH_SPLIT (bounces.rgen) also gets it summed into gByDepth: [0] depths 0 and 1
// (emission and direct light), [1] depth 2 (the first bounce), [2] depth 3 (the second), [3]
// depth 4 and more; the others compile without it.
//
// It also gets the light split by the first surface's lobes (shared/reference.h kRefLobes) in
// gByLobe: the first surface's next events are evaluated once per lobe (pathBrdf with
// gLobeMask) with the same random numbers, so the two sum to the one evaluation trace.rgen
// makes (each estimate is linear in the BRDF: the light table's resampled picks weigh their
// candidates by irradiance and cosine only); the light found past its scattered ray is shared
// by that direction's f_specular / f.
#ifdef TL_REFERENCE_DEPTH_SPLIT
vec3 gByDepth[4];
vec3 gByLobe[kRefLobes];
const int kLobeNone = -1;      // seen directly: emission, the sky
const int kLobeByShare = 2;    // past the first surface's scattered ray: by gSpecularShare
int gLobeTarget = kLobeNone;   // a lobe's index, or one of the two above
vec2 gLobeMask = vec2(1.0);    // the diffuse layer's and the specular lobes' weight in pathBrdf
vec3 gSpecularShare = vec3(0.0);
#endif
void gather(inout vec3 radiance, uint depth, vec3 light) {
  radiance += light;
#ifdef TL_REFERENCE_DEPTH_SPLIT
  gByDepth[clamp(depth, 1u, 4u) - 1u] += light;
  if (gLobeTarget == kLobeByShare) {
    gByLobe[1] += light * gSpecularShare;
    gByLobe[0] += light * (vec3(1.0) - gSpecularShare);
  } else if (gLobeTarget != kLobeNone) {
    gByLobe[gLobeTarget] += light;
  }
#endif
}

// The density with which a path leaving a surface draws direction l: tlSampleBrdf's, for the
// share of the paths that reflect rather than pass through (tlTransmissionProbability).
float pathPdf(SurfaceParams s, vec3 n, vec3 v, vec3 l, float pSpec) {
  return (1.0 - tlTransmissionProbability(s, dot(n, v))) * tlBrdfPdf(s, n, v, l, pSpec);
}

// The BRDF every next event evaluates (the split masks its lobes at the first surface).
vec3 pathBrdf(SurfaceParams s, vec3 n, vec3 v, vec3 l) {
#ifdef TL_REFERENCE_DEPTH_SPLIT
  return gLobeMask.x * tlBrdfDiffuse(s, n, v, l) + gLobeMask.y * tlBrdfSpecular(s, n, v, l);
#else
  return tlBrdf(s, n, v, l);
#endif
}



// What arrives along a shadow ray from `origin` in direction `dir` within `tMax`: 0 where an
// opaque surface or a volume's boundary is in the way, else what the thin transmitting surfaces
// crossed let through (shadow.rahit, shared/reference.h RefShadowRay).
vec3 shadowTransmittance(vec3 origin, vec3 dir, float tMax) {
  shadowRay.transmittance = vec3(1.0);
  shadowRay.reached = 0.0;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF, kRefShadowHitGroup, 0, 1,
              origin, 0.0, dir, tMax, 1);
  return shadowRay.reached > 0.0 ? shadowRay.transmittance : vec3(0.0);
}

// The light table (shared/lights.h) by next-event estimation from each scattering point: a
// shadow ray per light (per resampled pick beyond kLightsLoopMax lights). Delta lights cannot
// be hit by a BRDF-sampled ray; an area light can, so its sampled point (shared/area_lights.h)
// and the BRDF's rays that meet it (areaLightsMet) share it by the power heuristic.
vec3 gLightOrigin, gLightNormal, gLightGeometric, gLightView;
SurfaceParams gLightSurface;
vec3 gLightTint;
float lightVisibility(uint light, vec3 toLight, float distance) {
  if (dot(gLightGeometric, toLight) <= 0.0) return 0.0;
  vec3 through = shadowTransmittance(gLightOrigin, toLight, distance * (1.0 - 1e-4));
  float visibility = max(through.r, max(through.g, through.b));
  gLightTint = visibility > 0.0 ? through / visibility : vec3(0.0);
  return visibility;
}
vec3 lightTint() { return gLightTint; }
vec3 lightResponse(vec3 toLight) {
  float nl = dot(gLightNormal, toLight);
  return nl > 0.0 ? pathBrdf(gLightSurface, gLightNormal, gLightView, toLight) * nl : vec3(0.0);
}
float lightMisWeight(vec3 toLight, float lightPdf) {
  float pSpec = tlBrdfSpecularProbability(gLightSurface, dot(gLightNormal, gLightView));
  return tlPowerHeuristic(lightPdf, pathPdf(gLightSurface, gLightNormal, gLightView, toLight, pSpec));
}
#define TL_LIGHTS_AREA TL_AREA_SAMPLED
#define TL_LIGHTS_AREA_MIS
#define TL_LIGHTS_TINTED
#include "common/lights.glsl"
#include "common/environment.glsl"
#include "common/camera.glsl"

// The area lights a BRDF-drawn ray from `origin` meets between `tMin` and `tMax`, weighted
// against their next-event samples (directionPdf: the BRDF's density of dir; 0: nothing else
// drew it, weight 1). The origin is the point that drew the direction (the segments a path takes
// through transmitting surfaces start further on, at tMin), so the densities are those of its
// next events. Lights block nothing, so the path goes on to what lies behind. With more lights
// than kLightsLoopMax the next-event picks keep the whole weight and the rays count none.
vec3 areaLightsMet(vec3 origin, vec3 dir, float tMin, float tMax, float directionPdf) {
  vec3 sum = vec3(0.0);
  if (frame.lightCount > kLightsLoopMax) return sum;
  for (uint i = 0u; i < frame.lightCount; ++i) {
    if (!tlIsAreaLight(lights[i].type)) continue;
    AreaHit h = tlAreaLightHit(lights[i], origin, dir);
    if (!(h.t > tMin) || h.t >= tMax) continue;
    float w = directionPdf > 0.0 ? tlPowerHeuristic(directionPdf, h.pdf) : 1.0;
    sum += lights[i].intensity.rgb * w;
  }
  return sum;
}

// The scene's emissive triangles by next-event estimation (shared/emitters.h): one triangle
// drawn in proportion to its power (the material's average emission), a point uniform on it,
// rebuilt from its instance's camera-relative transform and its vertices, what the material
// emits there (texture and all: the average only chose the triangle), a shadow ray to it. The
// BRDF's rays that hit an emitter take the complementary power-heuristic weight (tracePath), so
// each light path is counted once. The point's pdf in solid angle is its triangle's
// probability / area x d^2 / |cos|, the same density a hit reads (refEmitterDensity).
vec3 emitterLight(vec3 origin, vec3 n, vec3 geometric, vec3 v, SurfaceParams s, float pSpec) {
  uvec3 h = nextHash();
  Emitter e = emitters[emitterPick(h.z, push.emitterCount)];
  uint instance = e.ids.x;
  RefInstanceGeometry g = geometry[instance];
  vec2 b = tlEmitterBarycentrics(vec2(tlUintToUnitFloat(h.x), tlUintToUnitFloat(h.y)));
  RefHitVertices hv = refHitVertices(g, e.ids.y, b);
  mat4 model = instances[instance].modelRelative;
  vec3 w = vec3(1.0 - b.x - b.y, b.x, b.y);
  vec3 point = vec3(model * vec4(hv.p0 * w.x + hv.p1 * w.y + hv.p2 * w.z, 1.0));
  float area = refWorldArea(model, hv);
  vec3 toLight = point - origin;
  float distance2 = dot(toLight, toLight);
  if (!(area > 0.0) || distance2 <= 0.0) return vec3(0.0);
  float distance = sqrt(distance2);
  vec3 l = toLight / distance;
  float nl = dot(n, l);
  if (nl <= 0.0 || dot(geometric, l) <= 0.0) return vec3(0.0);
  mat3 m = mat3(model);
  vec3 lightNormal = cross(m * (hv.p1 - hv.p0), m * (hv.p2 - hv.p0));
  float cosLight = abs(dot(lightNormal, l)) / (2.0 * area);
  if (!(cosLight > 0.0)) return vec3(0.0);
  GpuMaterial material = materials[g.material];
  vec3 emitted = materialEmissionLod0(material, hv.uv0, hv.uv1);
  vec4 base = materialBaseColorLod0(material, hv.uv0, hv.uv1, hv.color);
  // An unlit surface emits its base colour, as its hits report (trace.rchit).
  if ((material.flags & kMaterialUnlit) != 0u)
    emitted += clamp(tlMaterialBaseColor(base.rgb, tlFrameMaterials(frame.flags)), 0.0, 1.0);
  // Where a cut-out surface is not (alpha MASK), or not this time (BLEND: present with
  // probability alpha), the rays pass through it and find no emission either.
  float xi = tlUintToUnitFloat(tlPcgHash(h.z ^ 0x68E31DA4u));
  if (materialCutout(material, base.a, xi)) return vec3(0.0);
  if (dot(emitted, emitted) <= 0.0) return vec3(0.0);
  vec3 through = shadowTransmittance(origin, l, distance * (1.0 - 1e-4));
  if (all(equal(through, vec3(0.0)))) return vec3(0.0);
  float lightPdf = tlEmitterSolidAnglePdf(e.edge2.w, area, distance2, cosLight);
  float weight = tlPowerHeuristic(lightPdf, pathPdf(s, n, v, l, pSpec));
  return emitted * through * pathBrdf(s, n, v, l) * (nl * weight / lightPdf);
}

// The weight of emission a BRDF-drawn ray found (directionPdf: the BRDF's density of its
// direction; 0: nothing else could have drawn it) against emitter sampling's draw of that point
// from where the direction was drawn, `before` short of this segment's start (the surfaces it
// passed straight through).
float emissionWeight(vec3 dir, float directionPdf, float before) {
  if (push.emitterCount == 0u || !(directionPdf > 0.0) || !(hit.geometric.w > 0.0)) return 1.0;
  float cosLight = abs(dot(hit.geometric.xyz, dir));
  float distance = before + hit.positionT.w;
  float lightPdf = hit.geometric.w * distance * distance / max(cosLight, 1e-12);
  return tlPowerHeuristic(directionPdf, lightPdf);
}

// How many transmitting surfaces one segment of a path may pass straight through (a bound
// for the GPU's sake: past it the path ends).
const uint kPathCrossingsMax = 64u;

// A camera ray: what it meets first, passing the backs of single-sided surfaces as the raster
// culls them (glTF doubleSided, shared/scene.h). Each crossing restarts the ray just beyond the
// surface, up to kCameraRayCulledLayers of them (a bound for the GPU's sake: past it the ray
// stops at the back it met, shaded as the back side).
const uint kCameraRayCulledLayers = 64u;
void traceCameraRay(vec3 origin, vec3 dir) {
  traceRayEXT(tlas, gl_RayFlagsNoneEXT, 0xFF, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  for (uint layer = 0u; layer < kCameraRayCulledLayers && hit.positionT.w >= 0.0 && hit.normal.w > 0.0; ++layer) {
    origin = tlOffsetRayOrigin(hit.positionT.xyz, -hit.geometric.xyz, frame.sceneScale);
    traceRayEXT(tlas, gl_RayFlagsNoneEXT, 0xFF, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  }
}

// Ambient occlusion of this sample's primary hit (1 when the camera ray sees the sky): the
// ground truth the real-time paths' AO is measured against, at the same radius.
float gAo;

// The light sampled explicitly at a scattering point (next-event estimation): the sun, the
// light table, the emitters and the environment map, through pathBrdf.
void gatherNextEvents(inout vec3 radiance, uint bounce, vec3 throughput, vec3 position, vec3 n, vec3 geometric, vec3 v,
                      SurfaceParams s, float pSpec) {
  // The sun: a delta light, reached only by next-event estimation.
  vec3 toSun = frame.sunToLight.xyz;
  float sunNl = dot(n, toSun);
  if ((frame.flags & kFrameFlagSunShadows) != 0u && sunNl > 0.0 && dot(geometric, toSun) > 0.0) {
    vec3 through = shadowTransmittance(position, toSun, 1e30);
    gather(radiance, bounce + 1u, throughput * frame.sunIrradiance.rgb * through * sunNl * pathBrdf(s, n, v, toSun));
  }

  if (frame.lightCount > 0u) {
    gLightOrigin = position;
    gLightNormal = n;
    gLightGeometric = geometric;
    gLightView = v;
    gLightSurface = s;
    vec2 u = next2();
    gather(radiance, bounce + 1u, throughput * shadeLights(position, n, uvec3(floatBitsToUint(u.x), floatBitsToUint(u.y), gSample)));
  }

  if (push.emitterCount > 0u) gather(radiance, bounce + 1u, throughput * emitterLight(position, n, geometric, v, s, pSpec));

  // The environment map by next-event estimation: a direction drawn by its importance table,
  // weighted against the BRDF's density for it (the power heuristic); the BRDF's own
  // samples that escape take the complementary weight above.
  if (environmentMapOn()) {
    float envPdf;
    vec3 l = environmentSample(next2(), envPdf);
    float nl = dot(n, l);
    if (envPdf > 0.0 && nl > 0.0 && dot(geometric, l) > 0.0) {
      vec3 through = shadowTransmittance(position, l, 1e30);
      if (any(greaterThan(through, vec3(0.0)))) {
        float w = environmentMisWeight(envPdf, pathPdf(s, n, v, l, pSpec));
        gather(radiance, bounce + 1u, throughput * through * environmentRadiance(l) * pathBrdf(s, n, v, l) * (nl * w / envPdf));
      }
    }
  }
}

// Radiance arriving at `origin` from direction `dir`, where `firstBounce` scattering events
// have already happened (0: a camera ray; it also sets gAo).
vec3 tracePath(vec3 origin, vec3 dir, uint firstBounce) {
  gAo = 1.0;
#ifdef TL_REFERENCE_DEPTH_SPLIT
  gLobeTarget = kLobeNone;
#endif
  vec3 throughput = vec3(1.0), radiance = vec3(0.0);
  // The BRDF density of the direction being traced, for multiple importance sampling against
  // the environment map's samples; 0 where nothing else could have drawn it (the camera ray,
  // the caller's first direction).
  float directionPdf = 0.0;
  // Passing straight through a thin transmitting surface (shared/shading.h tlThinTransmittance)
  // is not a scattering event: the direction, its density and the bounce stay. `before` is how
  // far the direction has come from the point that drew it. The boundary of a volume
  // (KHR_materials_volume) refracts instead: a new direction, drawn by nothing else (a delta:
  // density 0, what it meets weighs 1, as no next event reaches through it). `medium` is the
  // absorption of the volume the path is in (one at a time, the camera outside every volume).
  float before = 0.0;
  vec3 medium = vec3(0.0);
  uint crossings = 0u;
  for (uint bounce = firstBounce;;) {
    // Only camera rays cull single-sided backs; every scattered ray sees both sides.
    if (bounce == 0u)
      traceCameraRay(origin, dir);
    else
      traceRayEXT(tlas, gl_RayFlagsNoneEXT, 0xFF, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
    // Area lights are not shown to the camera (no path draws them): only scattered rays see them.
    if (bounce > 0u && frame.lightCount > 0u)
      gather(radiance, bounce,
             throughput * areaLightsMet(origin - dir * before, dir, before, before + (hit.positionT.w < 0.0 ? 1e30 : hit.positionT.w),
                                        directionPdf));
    if (any(greaterThan(medium, vec3(0.0)))) throughput *= exp(-medium * (hit.positionT.w < 0.0 ? 1e30 : hit.positionT.w));
    if (hit.positionT.w < 0.0) {
      float w = environmentMapOn() && directionPdf > 0.0 ? environmentMisWeight(directionPdf, environmentPdf(dir)) : 1.0;
      gather(radiance, bounce, throughput * environmentRadiance(dir) * w);
      break;
    }
    gather(radiance, bounce, throughput * hit.emission.rgb * emissionWeight(dir, directionPdf, before));
    if (bounce >= push.maxBounces) break;  // no more scattering events allowed

    vec3 n = hit.normal.xyz, geometric = hit.geometric.xyz, v = -dir;
    SurfaceParams s = tlMaterialSurfaceLayered(hit.baseColor.rgb, hit.baseColor.a, hit.emission.a, hit.fresnel,
                                               hit.transmission.x, hit.coat.x, hit.coat.y, tlFrameMaterials(frame.flags));
    vec3 position = tlOffsetRayOrigin(hit.positionT.xyz, geometric, frame.sceneScale);

    if (bounce == 0u && push.aoRadius > 0.0) {
      // One cosine-distributed ray within the AO radius: the definition RTAO estimates.
      vec3 a = tlLocalToWorld(tlSampleCosineHemisphere(next2()), n);
      if (dot(geometric, a) > 0.0) {
        // What glass lets through counts as open (by luminance).
        gAo = tlLuminance(shadowTransmittance(position, a, push.aoRadius));
      } else {
        gAo = 0.0;  // the shading normal points into the surface here: treat as occluded
      }
    }

    float pSpec = tlBrdfSpecularProbability(s, dot(n, v));
#ifdef TL_REFERENCE_DEPTH_SPLIT
    if (bounce == 0u) {
      // Once per lobe of the first surface, with the same random numbers.
      uint dimension = gDimension;
      gLobeMask = vec2(1.0, 0.0), gLobeTarget = 0;
      gatherNextEvents(radiance, bounce, throughput, position, n, geometric, v, s, pSpec);
      gDimension = dimension;
      gLobeMask = vec2(0.0, 1.0), gLobeTarget = 1;
      gatherNextEvents(radiance, bounce, throughput, position, n, geometric, v, s, pSpec);
      gLobeMask = vec2(1.0);
    } else
#endif
      gatherNextEvents(radiance, bounce, throughput, position, n, geometric, v, s, pSpec);

    vec2 u = next2();
    vec2 choice = next2();
    float pThrough = tlTransmissionProbability(s, dot(n, v));
    if (choice.x < pThrough) {
      // Through the surface, the bounce not counted (a bound on the crossings instead): on in
      // the same direction, or refracted into or out of its volume by Snell's law. Where the
      // light cannot leave (total internal reflection) the share that would have passed is
      // reflected as by a mirror, and the path stays inside.
      throughput *= tlThinTransmittance(s, dot(n, v)) / pThrough;
      bool crossed = true;
      if (hit.transmission.y > 0.0) {
        bool leaving = hit.transmission.z > 0.0;
        float ior = max(hit.transmission.w, 1.0);
        vec3 refracted = refract(dir, n, leaving ? ior : 1.0 / ior);
        crossed = dot(refracted, refracted) > 0.0 && dot(refracted, geometric) < 0.0;
        dir = crossed ? normalize(refracted) : reflect(dir, n);
        if (!crossed && dot(dir, geometric) <= 0.0) break;
        if (crossed) medium = leaving ? vec3(0.0) : hit.absorption.rgb;
        directionPdf = 0.0;
        before = 0.0;
      } else {
        before += hit.positionT.w;
      }
      origin = tlOffsetRayOrigin(hit.positionT.xyz, crossed ? -geometric : geometric, frame.sceneScale);
#ifdef TL_REFERENCE_DEPTH_SPLIT
      if (bounce == 0u) gLobeTarget = kLobeNone;  // the next surface seen is the first to reflect
#endif
      if (++crossings > kPathCrossingsMax) break;
      continue;
    }
    choice.x = (choice.x - pThrough) / (1.0 - pThrough);

    // Next direction from the BRDF (shared/shading.h): the single-scattering lobe from its
    // visible normals, the rest by cosine, each in proportion to its albedo; weight f cos / pdf.
    vec3 l = tlSampleBrdf(s, n, v, pSpec, u, choice.x);
    float nl = dot(n, l);
    if (nl <= 0.0 || dot(geometric, l) <= 0.0) break;
    float pdf = (1.0 - pThrough) * tlBrdfPdf(s, n, v, l, pSpec);
    if (!(pdf > 1e-8)) break;
    vec3 f = tlBrdf(s, n, v, l);
    throughput *= f * (nl / pdf);
    directionPdf = pdf;
    before = 0.0;
    crossings = 0u;
#ifdef TL_REFERENCE_DEPTH_SPLIT
    if (bounce == 0u) {
      gSpecularShare = clamp(tlBrdfSpecular(s, n, v, l) / max(f, vec3(1e-30)), 0.0, 1.0);
      gLobeTarget = kLobeByShare;
    }
#endif

    // Russian roulette from the fourth scattering event on keeps long paths unbiased and cheap:
    // a path survives with the probability its throughput carries (at most 0.95, so even a
    // white surface ends), and survivors carry that much more. The hard cap (maxBounces,
    // default 64: RenderSettings::referenceBounces) is then almost never what ends a path.
    if (bounce >= 3u) {
      float q = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
      if (choice.y >= q) break;
      throughput /= q;
    }
    origin = position;
    dir = l;
    ++bounce;
  }
  return radiance;
}

// The camera ray through a jittered point of pixel p, camera-relative (common/camera.glsl).
CameraRay jitteredCameraRay(ivec2 p) {
  vec2 jitter = next2();
  return cameraRay((vec2(p) + jitter) * frame.viewport.zw * 2.0 - 1.0);
}
