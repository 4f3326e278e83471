// The body of the lights.direct pass (lights.comp: unshadowed; lights_shadowed.comp: shadow
// maps; lights_traced.comp: shadow rays by ray query): each G-buffer pixel lit by the light table through the shared BRDF. The
// includer declares the bindings below' common part and defines lightVisibility. The sum is
// the reflected radiance (rgb) and the luminance of its specular lobes' part (a), which
// composite.stages splits the image by (the reference's lobes, compare).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLightsPassBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kLightsPassNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kLightsPassMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kLightsPassDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLightsPassOutput, rgba16f) uniform writeonly image2D outRadiance;
layout(set = 0, binding = kLightsPassAccum, rgba32f) uniform image2D accum;
layout(set = 0, binding = kLightsPassAccumSpecular, r32f) uniform image2D accumSpecular;
layout(push_constant) uniform Push { LightsPush push; };

#include "common/camera.glsl"
#include "shared/area_specular.h"

SurfaceParams gSurface;
vec3 gPosition, gNormalHere, gView;  // the includer declares gShadowOrigin (where shadow rays start)

// The sum: radiance (rgb), its specular lobes' luminance (a).
#define TL_LIGHTS_CUSTOM_SUM
#define LightSum vec4
vec4 lightSumZero() { return vec4(0.0); }
vec4 lightSumAdd(vec4 a, vec4 b) { return a + b; }
vec4 lightSumScale(vec4 a, float k) { return a * k; }
vec4 lightContribution(uint light, LightIncidence li);

#include "common/lights.glsl"

vec4 diffuseAndSpecular(vec3 diffuse, vec3 specular) { return vec4(diffuse + specular, tlLuminance(specular)); }

// One light's reflected radiance with its visibility (no shadow ray for a light that cannot
// contribute). Area lights: the diffuse layer from the analytic term, the glossy lobes
// estimated by a point of the shape and a direction of the lobe (shared/area_specular.h),
// accumulated over frames.
vec4 lightContribution(uint light, LightIncidence li) {
  if (all(equal(li.irradiance, vec3(0.0)))) return vec4(0.0);
  float nl = dot(gNormalHere, li.toLight);
  vec3 diffuse = nl > 0.0 ? li.irradiance * tlBrdfDiffuse(gSurface, gNormalHere, gView, li.toLight) * nl : vec3(0.0);
  vec3 specular;
  if (li.pdf == 0.0 && tlIsAreaLight(lights[light].type)) {  // the analytic incidence
    vec4 u = areaGlossyDraws(light);
    specular = tlAreaLightSpecular(lights[light], gSurface, gNormalHere, gView, gPosition, u.xy, u.zw);
  } else {
    specular = nl > 0.0 ? li.irradiance * tlBrdfSpecular(gSurface, gNormalHere, gView, li.toLight) * nl : vec3(0.0);
  }
  if (all(equal(diffuse + specular, vec3(0.0)))) return vec4(0.0);
  return diffuseAndSpecular(diffuse, specular) * (lightVisibilityOf(light, li) * lightSampleWeight(li));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(outRadiance, p, vec4(0.0));
    if (push.accumulate != 0u) {
      imageStore(accum, p, vec4(0.0));
      imageStore(accumSpecular, p, vec4(0.0));
    }
    return;
  }
  vec3 position = cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth);
  gPosition = position;
  gNormalHere = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  gView = towardsViewer(position);
  vec4 material = texelFetch(gMaterial, p, 0);
  gSurface = tlGbufferSurface(texelFetch(gBaseColor, p, 0), material, tlFrameMaterials(frame.flags));
  gShadowOrigin = tlOffsetRayOrigin(position, gNormalHere, frame.sceneScale);
  vec4 radiance = shadeLights(position, gNormalHere, uvec3(uvec2(p), frame.frameIndex));
  if (push.accumulate != 0u) {
    // Each pixel counts its own estimates (a pixel that was sky starts over).
    vec4 sum = vec4(radiance.rgb, 1.0);
    float specular = radiance.a;
    if (push.restart == 0u) {
      sum += imageLoad(accum, p);
      specular += imageLoad(accumSpecular, p).r;
    }
    imageStore(accum, p, sum);
    imageStore(accumSpecular, p, vec4(specular));
    radiance = vec4(sum.rgb, specular) / sum.a;
  }
  imageStore(outRadiance, p, radiance);
}
