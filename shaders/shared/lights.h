// The scene's lights other than the sun (KHR_lights_punctual point, spot and further
// directional lights; rectangle, disk and tube area lights from the lighting sidecar,
// shared/area_lights.h), as every path shades them: one std430 array of GpuLight at set 0
// binding kBindingLights ("lights.table"), written each frame by the session with positions
// relative to the camera (lighting/common/light_table.h). A scene without such lights has no
// table: FrameConstants::lightCount is 0 and nothing reads the binding.
//
// Units. Twinlight's radiometric scale is glTF's photometric one divided by 683 lm/W (the
// luminous efficacy glTF exporters such as Blender's use to turn watts into lumens): a
// directional light of L lux has irradiance E = L / 683, a point or spot light of C candela has
// intensity I = C / 683, and a white Lambertian surface facing a light of irradiance E shows
// radiance E / pi. The sky (extras.twinlight.sky_radiance, --sky) and the CLI's --sun are
// already on that scale, so a Blender sun of strength S W/m^2, exported as 683 S lux, arrives
// as E = S next to a world of the same strength, as in Blender. An area light of N nits
// (cd/m^2) has radiance L = N / 683.
#ifndef TL_SHARED_LIGHTS_H
#define TL_SHARED_LIGHTS_H
#include "common.h"
#include "sampling.h"

TL_BEGIN
TL_CONST float kLumensPerWatt = 683.0f;

TL_CONST uint kLightDirectional = 0u;
TL_CONST uint kLightPoint = 1u;
TL_CONST uint kLightSpot = 2u;
TL_CONST uint kLightRect = 3u;  // area lights (shared/area_lights.h): every type from here on
TL_CONST uint kLightDisk = 4u;
TL_CONST uint kLightTube = 5u;

// Set-0 binding of the light table in every pass that shades lights (beside the BRDF tables').
TL_CONST uint kBindingLights = 49u;

// Bindings of the lights.direct pass (set 0; also kBindingFrame, kBindingBrdfTables, kBindingLights):
// the G-buffer it shades, its output, and the top level its shadow rays trace (rt only).
TL_CONST uint kLightsPassBaseColor = 1u;
TL_CONST uint kLightsPassNormal = 2u;
TL_CONST uint kLightsPassMaterial = 3u;
TL_CONST uint kLightsPassDepth = 4u;
TL_CONST uint kLightsPassOutput = 5u;
TL_CONST uint kLightsPassTlas = 6u;
TL_CONST uint kLightsPassAccum = 7u;          // rgba32f, persistent: sum of estimates (rgb) and their count (a)
TL_CONST uint kLightsPassAccumSpecular = 8u;  // r32f, persistent: sum of the estimates' specular lobes' luminance

// With more than kLightsLoopMax lights the pass's estimate is noisy: it accumulates while
// nothing it depends on changes (the frame key), like the reference, and writes the mean.
struct LightsPush {
  uint accumulate;  // 1: add this frame's estimate to the sum (more than kLightsLoopMax lights)
  uint restart;     // 1: the sum starts over this frame
  uint ibufferStage;    // redeferred form: kIbufferStage* (shared/redeferred.h)
  uint ibufferPattern;  // redeferred form: kIbufferPattern*
};

// Up to this many lights every shading point evaluates all of them (exact: no noise). With more,
// it takes kLightPicks lights, each chosen by resampled importance sampling among
// kLightCandidates drawn in proportion to power (GpuLight::intensity.w): the cost stays the same
// however many lights there are (a binary search per candidate), and the candidates' unshadowed
// contribution at the point (power and distance, cone and cosine) picks the one traced.
TL_CONST uint kLightsLoopMax = 8u;
TL_CONST uint kLightCandidates = 8u;
TL_CONST uint kLightPicks = 2u;

struct GpuLight {
  vec4 position;   // xyz: camera-relative position (point, spot; an area light's centre); w: range in metres (0: unlimited)
  vec4 direction;  // xyz: unit direction the light travels (directional; a spot's axis; a rectangle's or disk's front
                   // normal; a tube's axis); w: cumulative selection probability
  vec4 intensity;  // rgb: intensity I (point, spot), irradiance E (directional) or radiance L (area), Twinlight units;
                   // w: selection probability
  float cosOuter;  // spot: cos(outer cone angle); -1 otherwise
  float coneScale; // spot: 1 / max(cos inner - cos outer, 1e-3)
  uint type;       // kLight*
  uint shadowView; // first of its shadow views (shared/lights.h GpuShadowView; 6 for a cube), kNoLightShadow: none
  vec4 axisU;      // area: xyz half the width (rectangle), the radius (disk) or half the length (tube) along the
                   // shape's first axis; w: a tube's radius
  vec4 axisV;      // area: xyz the second half-extent (u x v along the front normal; a tube: 0); w: 1 two-sided
};

// Shadow maps of point, spot and area lights (the direct and legacy paths; rt and the reference
// trace shadow rays). Every shadowed light has perspective views of 90 degrees or less, each one
// tile of the depth atlas "shadow.lightsDepth" (D32F, standard Z: 0 at the near plane): a spot
// whose cone fits kLightShadowMaxSpotTan one view along its axis, a point light, a wider spot or
// an area light (from its centre) six, a cube's faces in the order +x -x +y -y +z -z. Each view's field of view is widened by
// kLightShadowGuardTexels on every side, so the filter's taps for the directions the view owns
// never leave its tile. The views are "lights.shadowViews" at kBindingLightShadowViews.
TL_CONST uint kNoLightShadow = 0xFFFFFFFFu;
TL_CONST float kLightShadowGuardTexels = 4.0f;
TL_CONST float kLightShadowMaxSpotTan = 1.7320508f;  // tan 60 degrees: wider spots take a cube
// A shadow view's near plane as a share of its far plane (2 cm for a 20 m reach): a length of
// the scene's, not a constant in metres, so a scene at any scale keeps the same depth precision.
TL_CONST float kLightShadowNearShare = 1e-3f;
// Receivers are pushed along their normal and towards the light by these many texels of the
// map at their distance (world units grow with distance in a perspective map).
TL_CONST float kLightShadowNormalOffsetTexels = 1.5f;
TL_CONST float kLightShadowBiasTexels = 2.0f;
TL_CONST uint kBindingLightShadowViews = 52u;
TL_CONST uint kBindingLightShadowAtlas = 53u;  // sampler2DShadow over shadow.lightsDepth
TL_CONST uint kBindingLightShadowDepth = 54u;  // the same atlas, plain: an area light's blocker search
// An area light's soft shadow (common/light_shadow.glsl) searches for blockers and filters over
// at most this tangent of the angle seen from the light (about 31 degrees).
TL_CONST float kAreaShadowMaxTan = 0.6f;

struct GpuShadowView {
  mat4 viewProj;  // camera-relative world -> this view's clip space (Vulkan, z in [0,1])
  vec4 tile;      // xy: the tile's corner in the atlas (uv), zw: its size (uv)
  vec4 params;    // x: near, y: far (metres), z: texel size per metre of depth (2 tan(fov/2) / tile texels), w: the light's view count (1 or 6)
};

// Push constants of the shadow.lights raster: the view drawn.
struct LightShadowPush {
  uint view;
  uint pad0, pad1, pad2;
};

// The depth a receiver at view depth w (metres along the view's axis) has in its view's map:
// glm::perspectiveRH_ZO's z / w.
TL_FN float tlShadowViewDepth(float nearPlane, float farPlane, float w) {
  return farPlane / (farPlane - nearPlane) * (1.0f - nearPlane / max(w, nearPlane));
}

// Its inverse: the view depth (metres) of a map depth.
TL_FN float tlShadowViewW(float nearPlane, float farPlane, float depth) {
  return nearPlane / max(1.0f - depth * (farPlane - nearPlane) / farPlane, 1e-6f);
}

// Which of a cube's six views (+x -x +y -y +z -z) sees direction d from the light.
TL_FN uint tlCubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0f ? 2u : 3u;
  return d.z >= 0.0f ? 4u : 5u;
}

// Where direction (or point) d from a cube's centre lands in the view of `face` (its axis the
// largest of d's): (x, y) / w in that view's camera, before the projection's 1 / tan(fov / 2),
// and the view depth w. Equal to the face's viewProj (glm::lookAtRH with up +y, or +z for the
// y faces, as light_shadows.cpp builds it; checked in tests/unit/test_light_shadows.cpp), without
// a matrix: an area light's soft-shadow taps each take a face of their own.
TL_FN vec3 tlCubeFaceProject(uint face, vec3 d) {
  // Per face: the view's right (s) and up (u) axes and its forward f; x = s.d, y = u.d, w = f.d.
  if (face == 0u) return vec3(d.z / d.x, d.y / d.x, d.x);      // +x: s = +z, u = +y
  if (face == 1u) return vec3(-d.z / -d.x, d.y / -d.x, -d.x);  // -x: s = -z, u = +y
  if (face == 2u) return vec3(d.x / d.y, d.z / d.y, d.y);      // +y: s = +x, u = +z
  if (face == 3u) return vec3(-d.x / -d.y, d.z / -d.y, -d.y);  // -y: s = -x, u = +z
  if (face == 4u) return vec3(-d.x / d.z, d.y / d.z, d.z);     // +z: s = -x, u = +y
  return vec3(d.x / -d.z, d.y / -d.z, -d.z);                    // -z: s = +x, u = +y
}

// What a light sends to a point: the unit direction towards it, its distance (1e30 for a
// directional light) and the irradiance on a surface facing it there (times n.l for irradiance).
// Area lights (shared/area_lights.h) give either the whole shape's light (pdf 0) or one sampled
// point's, with its solid-angle pdf.
struct LightIncidence {
  vec3 toLight;
  float distance;
  vec3 irradiance;
  float pdf;  // a sampled area light's density of toLight per steradian; 0: deterministic
};

// KHR_lights_punctual's recommended cone falloff: 0 outside the outer cone, 1 inside the
// inner one, and the square of a linear ramp in the cosine between them.
TL_FN float tlSpotAttenuation(float cosOuter, float coneScale, float cosAngle) {
  float t = tlSaturate((cosAngle - cosOuter) * coneScale);
  return t * t;
}

// KHR_lights_punctual's recommended range window: the inverse square law, brought smoothly to
// zero at the range (max(1 - (d / range)^4, 0)); 1 without a range.
TL_FN float tlLightRangeWindow(float distance, float range) {
  if (!(range > 0.0f)) return 1.0f;
  float r = distance / range;
  r = r * r;
  return tlSaturate(1.0f - r * r);
}

TL_END
#include "area_lights.h"
TL_BEGIN

// The light's incidence at `position`; an area light's whole unshadowed shape (tlAreaLightAnalytic).
TL_FN LightIncidence tlLightIncidence(GpuLight light, vec3 position) {
  if (tlIsAreaLight(light.type)) return tlAreaLightAnalytic(light, position);
  LightIncidence li;
  li.pdf = 0.0f;
  if (light.type == kLightDirectional) {
    li.toLight = -vec3(light.direction);
    li.distance = 1e30f;
    li.irradiance = vec3(light.intensity);
    return li;
  }
  vec3 d = vec3(light.position) - position;
  float d2 = max(dot(d, d), 1e-12f);
  li.distance = sqrt(d2);
  li.toLight = d / li.distance;
  float cone = light.type == kLightSpot ? tlSpotAttenuation(light.cosOuter, light.coneScale, -dot(vec3(light.direction), li.toLight))
                                        : 1.0f;
  li.irradiance = vec3(light.intensity) * (cone * tlLightRangeWindow(li.distance, light.position.w) / d2);
  return li;
}

// What resampling keeps a candidate by: its unshadowed irradiance at the point times the
// cosine (luminance), the part of the light's contribution that does not depend on the BRDF.
TL_FN float tlLightTarget(LightIncidence li, vec3 n) {
  return tlLuminance(li.irradiance) * max(dot(n, li.toLight), 0.0f);
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::GpuLight) == 96);
static_assert(sizeof(tl::shared::GpuShadowView) == 96);
static_assert(sizeof(tl::shared::LightShadowPush) == 16);
#endif
#endif
