#version 460
// The composite's intermediate quantities as images, for per-stage error against the
// reference (reference.ao, reference.irradiance): the AO and the diffuse irradiance the
// composite multiplies, from the same code. Only frames that read them run this pass.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/packing.h"
#include "shared/shading.h"
#include "shared/sh.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kCompositeBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kCompositeNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kCompositeMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kCompositeDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kCompositeStageAo, r16f) uniform writeonly image2D outAo;
layout(set = 0, binding = kCompositeStageIrradiance, rgba16f) uniform writeonly image2D outIrradiance;
layout(push_constant) uniform Push { CompositePush push; };

#include "common/camera.glsl"
#include "common/path_indirect.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: no surface, nothing to measure (the reference writes 0 too)
    imageStore(outAo, p, vec4(0.0));
    imageStore(outIrradiance, p, vec4(0.0));
    return;
  }
  vec3 position = cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  float ao = pathAmbientOcclusion(p);
  imageStore(outAo, p, vec4(ao));
  // The surface only for its albedo: what occlusion puts back (path_indirect.glsl).
  vec4 material = texelFetch(gMaterial, p, 0);
  SurfaceParams s = tlGbufferSurface(texelFetch(gBaseColor, p, 0), material, tlFrameMaterials(frame.flags));
  vec3 irradiance = pathDiffuseIrradiance(p, n, position, ao, tlHemisphericalAlbedo(s), tlSkyIrradiance(frame, n));
  // As the composite applies it: times the material's occlusion (gbuffer.material.a).
  imageStore(outIrradiance, p, vec4(material.w * irradiance, 1.0));
}
