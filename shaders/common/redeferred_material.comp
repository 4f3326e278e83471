#version 460
// redeferred.material: the I-buffer (shared/redeferred.h) resolved against each pixel's
// material at full resolution, plus what does not factor into material-free sums of light:
// emission, the indirect specular (the path's SH through a lobe whose roughness the light's
// directionality sets, or the sky's, times multi-bounce AO) and the light multi-bounce AO
// puts back for the surface's own albedo. Writes the same radiance image as the composite.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/gbuffer.h"
#include "shared/packing.h"
#include "shared/redeferred.h"
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
layout(set = 0, binding = kCompositeOutput, rgba32f) uniform writeonly image2D outRadiance;  // kCompositeHdrFormat
layout(set = 0, binding = kIbufferSumDg) uniform sampler2D iDg;
layout(set = 0, binding = kIbufferSumSg1) uniform sampler2D iSg1;
layout(set = 0, binding = kIbufferSumSg2) uniform sampler2D iSg2;
layout(set = 0, binding = kIbufferSumMs) uniform sampler2D iMs;
layout(push_constant) uniform Push { CompositePush push; };

#include "common/camera.glsl"
#include "common/environment.glsl"
#include "common/path_indirect.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // reversed Z: nothing drawn, the sky is visible
    vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    imageStore(outRadiance, p, vec4(environmentRadiance(cameraRay(ndc).direction), 1.0));  // as the composite's
    return;
  }
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  vec3 position = cameraRelativePosition(uv, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 v = towardsViewer(position);
  vec4 material = texelFetch(gMaterial, p, 0);
  SurfaceParams s = tlGbufferSurface(texelFetch(gBaseColor, p, 0), material, tlFrameMaterials(frame.flags));

  IbufferSums sums;
  sums.dg = texelFetch(iDg, p, 0).rgb;
  sums.sg1 = texelFetch(iSg1, p, 0).rgb;
  sums.sg2 = texelFetch(iSg2, p, 0).rgb;
  sums.ms = texelFetch(iMs, p, 0).rgb;
  vec3 radiance = texelFetch(gEmissive, p, 0).rgb + tlIbufferResolve(s, dot(n, v), sums);
  // Multi-bounce AO's put-back: the irradiance for this albedo less the black surface's the
  // I-buffer holds (path_indirect.glsl), through the diffuse layer like the composite's.
  float ao = pathAmbientOcclusion(p);
  vec3 skyIrradiance = tlSkyIrradiance(frame, n);
  vec3 putBack = pathDiffuseIrradiance(p, n, position, ao, tlHemisphericalAlbedo(s), skyIrradiance) -
                 pathDiffuseIrradiance(p, n, position, ao, vec3(0.0), skyIrradiance);
  // The material's occlusion (gbuffer.material.a) on both indirect terms, as in the composite
  // (ibuffer.light applied it to the black surface's share).
  radiance += tlEnvironmentDiffuse(s, dot(n, v)) * kInvPi * (material.w * putBack);
  radiance += material.w * pathSpecular(p, n, v, position, ao, s, tlSkyRadiance(frame, reflect(-v, n)));
  imageStore(outRadiance, p, vec4(radiance, 1.0));
}
