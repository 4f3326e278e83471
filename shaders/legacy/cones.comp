#version 460
// Diffuse cone tracing through the voxel clipmap (Crassin et al. 2011; VXGI/VXAO): six 60
// degree cones around the normal gather voxel radiance front to back through the opacity,
// escaping light sees the sky. The same cones' opacity within the AO radius is voxel AO.
// The result is encoded in the RT path's SH luma + CoCg layout so the composite is shared.
#extension GL_GOOGLE_include_directive : require
#include "legacy/legacy_common.glsl"
#include "shared/sampling.h"
#include "shared/sh.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingConeShY, rgba16f) uniform writeonly image2D shYOut;
layout(set = 0, binding = kLegacyBindingConeCoCgAo, rgba16f) uniform writeonly image2D coCgAoOut;
#include "legacy/voxel_cones.glsl"

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, reducedSize(push.coneDivisor)))) return;
  ivec2 p = fullPixel(q, push.coneDivisor);
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(shYOut, q, vec4(0.0));
    imageStore(coCgAoOut, q, vec4(0.0, 0.0, 1.0, 0.0));  // w 0: sky
    return;
  }
  vec3 P = pixelPosition(p, depth);
  vec3 n = pixelNormal(p);
  float voxel = push.clipmap.levelMin[0].w;
  vec3 origin = P + n * (1.5 * voxel);  // leave the surface's own voxel
  mat3 basis = tlBasisFromNormal(n);
  // Cosine weights of one axial and five tilted cones, summing to pi (shared/legacy.h).
  const float wAxis = kLegacyConeAxisWeight, wRing = wAxis * kLegacyConeRingCos;
  ShLumaCoCg sh = tlShZero();
  float ao = 0.0;
  // Sealed air holds no light: no cone can gather any there (the cones' coarse texels would
  // otherwise blend in light from beyond its walls).
  const bool open = lightReaches(origin);
  for (int i = 0; i < 6; ++i) {
    vec3 local = vec3(0.0, 0.0, 1.0);
    if (i > 0) {
      float phi = float(i - 1) * 1.2566371;
      local = vec3(sin(kLegacyConeRingTilt) * cos(phi), sin(kLegacyConeRingTilt) * sin(phi), cos(kLegacyConeRingTilt));
    }
    vec3 dir = basis * local;
    ConeMarch cone = marchCone(origin, n, dir, kLegacyConeTanHalfAperture, push.coneRange, 0.95, push.aoRadius);
    vec3 radiance = open ? cone.gathered + (1.0 - cone.occlusion) * tlSkyRadiance(frame, dir) : vec3(0.0);
    float w = i == 0 ? wAxis : wRing;
    float cosTheta = local.z;
    sh = tlShAdd(sh, tlShScale(tlShProjectRadiance(dir, radiance), w / (0.25 + 0.5 * cosTheta)));
    ao += w * (1.0 - cone.nearOcclusion);
  }
  sh = tlShFitHalf(sh);  // into the RGBA16F range as a whole (shared/sh.h)
  imageStore(shYOut, q, sh.shY);
  imageStore(coCgAoOut, q, vec4(sh.coCg, ao / 3.14159265, depthToViewW(depth)));  // w: view depth for the upsample
}
