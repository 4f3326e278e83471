// The body of the lights.direct pass (lights.comp: unshadowed; lights_shadowed.comp: shadow
// maps; lights_traced.comp: shadow rays by ray query): each G-buffer pixel lit by the light table through the shared BRDF. The
// includer declares the bindings below' common part and defines lightVisibility.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLightsPassBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kLightsPassNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kLightsPassMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kLightsPassDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLightsPassOutput, rgba16f) uniform writeonly image2D outRadiance;
layout(set = 0, binding = kLightsPassAccum, rgba32f) uniform image2D accum;
layout(push_constant) uniform Push { LightsPush push; };

#include "common/camera.glsl"
#include "shared/area_specular.h"

SurfaceParams gSurface;
vec3 gPosition, gNormalHere, gView;  // the includer declares gShadowOrigin (where shadow rays start)

vec3 lightResponse(vec3 toLight) {
  float nl = dot(gNormalHere, toLight);
  return nl > 0.0 ? tlBrdf(gSurface, gNormalHere, gView, toLight) * nl : vec3(0.0);
}

// Area lights: the diffuse layer from the analytic term, the glossy lobes estimated by a point of
// the shape and a direction of the lobe (shared/area_specular.h), accumulated over frames.
#define TL_LIGHTS_AREA_GLOSSY
vec3 areaLightReflection(uint light, LightIncidence li);

#include "common/lights.glsl"

vec3 areaLightReflection(uint light, LightIncidence li) {
  float nl = dot(gNormalHere, li.toLight);
  vec3 diffuse = nl > 0.0 ? li.irradiance * tlBrdfDiffuse(gSurface, gNormalHere, gView, li.toLight) * nl : vec3(0.0);
  vec4 u = areaGlossyDraws(light);
  return diffuse + tlAreaLightSpecular(lights[light], gSurface, gNormalHere, gView, gPosition, u.xy, u.zw);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(outRadiance, p, vec4(0.0));
    if (push.accumulate != 0u) imageStore(accum, p, vec4(0.0));
    return;
  }
  vec3 position = cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth);
  gPosition = position;
  gNormalHere = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  gView = towardsViewer(position);
  vec4 material = texelFetch(gMaterial, p, 0);
  gSurface = tlGbufferSurface(texelFetch(gBaseColor, p, 0), material, tlFrameMaterials(frame.flags));
  gShadowOrigin = tlOffsetRayOrigin(position, gNormalHere, frame.sceneScale);
  vec3 radiance = shadeLights(position, gNormalHere, uvec3(uvec2(p), frame.frameIndex));
  if (push.accumulate != 0u) {
    vec4 sum = vec4(radiance, 1.0);
    if (push.restart == 0u) sum += imageLoad(accum, p);
    imageStore(accum, p, sum);
    radiance = sum.rgb / sum.a;
  }
  imageStore(outRadiance, p, vec4(radiance, 1.0));
}
