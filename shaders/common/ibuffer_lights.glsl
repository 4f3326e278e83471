// The body of lights.direct in redeferred form (ibuffer_lights.comp: unshadowed;
// ibuffer_lights_shadowed.comp: shadow maps; ibuffer_lights_traced.comp: shadow rays by ray query): the light table's share of the
// I-buffer (shared/redeferred.h) at every G-buffer pixel, from the same picks as
// lights_shade.glsl (the same seeds), so the material pass rebuilds exactly its radiance.
// The includer declares the common bindings and defines lightVisibility.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLightsPassNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kLightsPassMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kLightsPassDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kIbufferOutDg, rgba32f) uniform writeonly image2D outDg;
layout(set = 0, binding = kIbufferOutSg1, rgba32f) uniform writeonly image2D outSg1;
layout(set = 0, binding = kIbufferOutSg2, rgba32f) uniform writeonly image2D outSg2;
layout(set = 0, binding = kIbufferOutMs, rgba32f) uniform writeonly image2D outMs;
layout(set = 0, binding = kIbufferAccumDg, rgba32f) uniform image2D accumDg;
layout(set = 0, binding = kIbufferAccumSg1, rgba32f) uniform image2D accumSg1;
layout(set = 0, binding = kIbufferAccumSg2, rgba32f) uniform image2D accumSg2;
layout(set = 0, binding = kIbufferAccumMs, rgba32f) uniform image2D accumMs;
layout(set = 0, binding = kIbufferRefineMaskSampled) uniform sampler2D refineMask;
layout(push_constant) uniform Push { LightsPush push; };

#include "common/camera.glsl"
#include "common/ibuffer_stage.glsl"
#include "shared/area_specular.h"

SurfaceParams gGeometry;  // the surface's roughness only (tlIbufferSurface)
vec3 gPosition, gNormalHere, gView;  // the includer declares gShadowOrigin (where shadow rays start)

float lightVisibilityOf(uint light, LightIncidence li);  // common/lights.glsl
#define TL_LIGHTS_CUSTOM_SUM
#define LightSum IbufferSums
IbufferSums lightSumZero() { return tlIbufferZero(); }
IbufferSums lightSumAdd(IbufferSums a, IbufferSums b) { return tlIbufferAdd(a, b); }
IbufferSums lightSumScale(IbufferSums a, float k) { return tlIbufferScale(a, k); }
IbufferSums lightContribution(uint light, LightIncidence li);  // below

#include "common/lights.glsl"

// An area light as lights_shade.glsl shades it: the diffuse layer from the analytic incidence, the
// lobes from the same two samples of the shape and of the lobe (shared/area_specular.h), added
// to the specular sums only; the visibility scales both.
IbufferSums areaLightSums(uint light, LightIncidence li) {
  if (all(equal(li.irradiance, vec3(0.0)))) return tlIbufferZero();
  float visibility = lightVisibilityOf(light, li);
  if (!(visibility > 0.0)) return tlIbufferZero();
  IbufferSums sums = tlIbufferZero();
  sums.dg = tlIbufferAddLight(tlIbufferZero(), gGeometry, gNormalHere, gView, li.toLight, li.irradiance * dot(gNormalHere, li.toLight)).dg;
  vec4 u = areaGlossyDraws(light);
  AreaSpecularSamples r = tlAreaLightSpecularSamples(lights[light], gGeometry, gNormalHere, gView, gPosition, u.xy, u.zw);
  IbufferSums lobes = tlIbufferAddLight(tlIbufferZero(), gGeometry, gNormalHere, gView, r.towardsShape, r.shapeWeight);
  lobes = tlIbufferAddLight(lobes, gGeometry, gNormalHere, gView, r.alongLobe, r.lobeWeight);
  lobes.dg = vec3(0.0);
  return tlIbufferScale(tlIbufferAdd(sums, lobes), visibility);
}

// One light's share, with its visibility; no shadow ray where it cannot contribute (lit from
// behind, or no irradiance), as in lights_shade.glsl.
IbufferSums lightContribution(uint light, LightIncidence li) {
  if (li.pdf == 0.0 && tlIsAreaLight(lights[light].type)) return areaLightSums(light, li);
  if (all(equal(li.irradiance, vec3(0.0))) || !(dot(gNormalHere, li.toLight) > 0.0)) return tlIbufferZero();
  // tlLightIncidence's irradiance is at normal incidence; the I-buffer sums E n.l.
  float nl = dot(gNormalHere, li.toLight);
  float visibility = lightVisibilityOf(light, li);
  return tlIbufferAddLight(tlIbufferZero(), gGeometry, gNormalHere, gView, li.toLight, li.irradiance * (nl * visibility));
}

// The running mean of one sum (many lights: each frame's estimate is noisy). A macro: GLSL
// takes no image of a declared format as a parameter.
#define ACCUMULATE(image, p, estimate)                          \
  {                                                             \
    vec4 sum = vec4(estimate, 1.0);                             \
    if (push.restart == 0u) sum += imageLoad(image, p);         \
    imageStore(image, p, sum);                                  \
    estimate = sum.rgb / sum.a;                                 \
  }

void main() {
  ivec2 p = ibufferStagePixel(push.ibufferStage, push.ibufferPattern);
  if (p.x < 0) {
    // The refining run's sums (many lights; their own images) start over at every pixel with
    // the pattern's, so a pixel refined later in the same sum adds only estimates of it.
    ivec2 g = ivec2(gl_GlobalInvocationID.xy);
    if (push.ibufferStage == kIbufferStageRefine && push.accumulate != 0u && push.restart != 0u &&
        all(lessThan(g, ivec2(frame.viewport.xy)))) {
      imageStore(accumDg, g, vec4(0.0));
      imageStore(accumSg1, g, vec4(0.0));
      imageStore(accumSg2, g, vec4(0.0));
      imageStore(accumMs, g, vec4(0.0));
    }
    return;
  }
  float depth = texelFetch(gDepth, p, 0).r;
  IbufferSums sums = tlIbufferZero();
  if (depth > 0.0) {
    vec3 position = cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth);
    gPosition = position;
    gNormalHere = tlOctDecode(texelFetch(gNormal, p, 0).xy);
    gView = towardsViewer(position);
    float roughness = tlMaterialRoughness(texelFetch(gMaterial, p, 0).x, tlFrameMaterials(frame.flags));
    gGeometry = tlIbufferSurface(roughness, tlFrameMaterials(frame.flags));
    gShadowOrigin = tlOffsetRayOrigin(position, gNormalHere, frame.sceneScale);
    sums = shadeLights(position, gNormalHere, uvec3(uvec2(p), frame.frameIndex));
  }
  if (push.accumulate != 0u) {
    ACCUMULATE(accumDg, p, sums.dg)
    ACCUMULATE(accumSg1, p, sums.sg1)
    ACCUMULATE(accumSg2, p, sums.sg2)
    ACCUMULATE(accumMs, p, sums.ms)
  }
  imageStore(outDg, p, vec4(sums.dg, 1.0));
  imageStore(outSg1, p, vec4(sums.sg1, 1.0));
  imageStore(outSg2, p, vec4(sums.sg2, 1.0));
  imageStore(outMs, p, vec4(sums.ms, 1.0));
}
