#version 460
// Composite shared by every lighting path: sun through the shadow map, the light table's
// radiance (lights.direct), the sky (times AO when a path provides it), emission. Output is scene-linear radiance.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/packing.h"
#include "shared/shading.h"
#include "shared/sh.h"
#include "shared/environment.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kCompositeBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kCompositeNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kCompositeMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kCompositeEmissive) uniform sampler2D gEmissive;
layout(set = 0, binding = kCompositeDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kCompositeShadow) uniform sampler2DShadow sunShadow;
layout(set = 0, binding = kCompositeOutput, rgba32f) uniform writeonly image2D outRadiance;  // kCompositeHdrFormat
layout(set = 0, binding = kCompositeLights) uniform sampler2D lightsRadiance;
layout(set = 0, binding = kCompositeSunVisibility) uniform sampler2D sunVisibilityHybrid;
layout(push_constant) uniform Push { CompositePush push; };

#include "common/camera.glsl"
#include "common/environment.glsl"
#include "common/path_indirect.glsl"

#define TL_SUN_SHADOW_PCSS
#define TL_SUN_VISIBILITY_HYBRID
layout(set = 0, binding = kCompositeShadowDepth) uniform sampler2D sunShadowDepth;
#include "common/sun_shadow.glsl"
#include "common/composite_lobes.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // reversed Z: nothing drawn, the sky is visible
    vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    // The background is the map itself (its texels), as the reference's escaping rays see it.
    imageStore(outRadiance, p, vec4(environmentRadiance(cameraRay(ndc).direction), 1.0));
    return;
  }
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  vec3 position = cameraRelativePosition(uv, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 v = towardsViewer(position);
  vec4 baseColor = texelFetch(gBaseColor, p, 0);
  vec4 material = texelFetch(gMaterial, p, 0);
  SurfaceParams s = tlGbufferSurface(baseColor, material, tlFrameMaterials(frame.flags));

  // Emission, the sun and the indirect light (common/composite_lobes.glsl), and the point, spot
  // and further directional lights (lights.direct), when the scene has any.
  CompositeLobes lobes = compositeLobes(p, position, n, v, s, material);
  vec3 radiance = texelFetch(gEmissive, p, 0).rgb + lobes.diffuse + lobes.specular;
  if ((push.flags & kCompositeHasLights) != 0u) radiance += texelFetch(lightsRadiance, p, 0).rgb;
  imageStore(outRadiance, p, vec4(radiance, 1.0));
}
