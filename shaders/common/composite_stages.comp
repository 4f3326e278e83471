#version 460
// The composite's intermediate quantities as images, for per-stage error against the
// reference (reference.ao, reference.irradiance, reference.diffuse and .specular): the AO and
// the diffuse irradiance the composite multiplies, and the radiance it adds through the
// surface's diffuse layer and through its specular lobes (the sun's, the light table's, the
// indirect), from the same code. Only frames that read them run this pass.
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
layout(set = 0, binding = kCompositeDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kCompositeStageAo, r16f) uniform writeonly image2D outAo;
layout(set = 0, binding = kCompositeStageIrradiance, rgba16f) uniform writeonly image2D outIrradiance;
layout(set = 0, binding = kCompositeStageDiffuse, rgba16f) uniform writeonly image2D outDiffuse;
layout(set = 0, binding = kCompositeStageSpecular, rgba16f) uniform writeonly image2D outSpecular;
layout(set = 0, binding = kCompositeShadow) uniform sampler2DShadow sunShadow;
layout(set = 0, binding = kCompositeLights) uniform sampler2D lightsRadiance;
layout(set = 0, binding = kCompositeSunVisibility) uniform sampler2D sunVisibilityHybrid;
layout(push_constant) uniform Push { CompositePush push; };

#include "common/camera.glsl"
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
  if (depth <= 0.0) {  // the sky: no surface, nothing to measure (the reference writes 0 too)
    imageStore(outAo, p, vec4(0.0));
    imageStore(outIrradiance, p, vec4(0.0));
    imageStore(outDiffuse, p, vec4(0.0));
    imageStore(outSpecular, p, vec4(0.0));
    return;
  }
  vec3 position = cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec4 material = texelFetch(gMaterial, p, 0);
  SurfaceParams s = tlGbufferSurface(texelFetch(gBaseColor, p, 0), material, tlFrameMaterials(frame.flags));
  // Each term of the composite through the lobe that reflects it, and the AO and irradiance
  // it multiplied (the irradiance as it applies it: times the material's occlusion).
  CompositeLobes lobes = compositeLobes(p, position, n, towardsViewer(position), s, material);
  imageStore(outAo, p, vec4(lobes.ao));
  imageStore(outIrradiance, p, vec4(lobes.irradiance, 1.0));
  vec3 diffuse = lobes.diffuse, specular = lobes.specular;
  if ((push.flags & kCompositeHasLights) != 0u) {
    // lights.direct: its radiance, and its specular part's luminance (a); the part takes the
    // whole's colour (exact in luminance, which compare measures).
    vec4 lights = texelFetch(lightsRadiance, p, 0);
    float luminance = tlLuminance(lights.rgb);
    float share = luminance > 0.0 ? clamp(lights.a / luminance, 0.0, 1.0) : 0.0;
    diffuse += lights.rgb * (1.0 - share);
    specular += lights.rgb * share;
  }
  imageStore(outDiffuse, p, vec4(diffuse, 1.0));
  imageStore(outSpecular, p, vec4(specular, 1.0));
}
