#version 460
// Bent-normal sky occlusion (the distance-field AO of Unreal 4 and the bent normals of Klehm
// et al. 2011, traced here with ray queries): per pixel, cosine-distributed rays within
// rtRayLength; V is the share that escapes (the cosine-weighted visibility) and the bent
// normal the mean direction of those that do. Irradiance = V x the sky's irradiance along the
// bent normal: exact for a uniform sky (V pi L; the open plane: pi L), the classic
// approximation for an environment map; no light bounces (that is what it is compared for).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/sampling.h"
#include "shared/sh.h"
#include "bent_sky.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kBentSkyNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kBentSkyDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kBentSkyTlas) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = kBentSkyHistory, rgba32f) uniform image2D history;
layout(set = 0, binding = kBentSkyShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kBentSkyCoCg, rg16f) uniform writeonly image2D outCoCg;
layout(set = 0, binding = kBentSkyAo, r16f) uniform writeonly image2D outAo;
layout(push_constant) uniform Push { BentSkyPush push; };

#include "common/camera.glsl"

bool escapes(vec3 origin, vec3 direction) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xFF, origin, 0.0, direction,
                        push.rayLength);
  while (rayQueryProceedEXT(q)) {}
  return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: nothing to occlude (the composite shows the sky there)
    imageStore(history, p, vec4(0.0));
    imageStore(outShY, p, vec4(0.0));
    imageStore(outCoCg, p, vec4(0.0));
    imageStore(outAo, p, vec4(1.0));
    return;
  }
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 origin = tlOffsetRayOrigin(pixelPosition(p, depth), n, frame.sceneScale);
  mat3 basis = tlBasisFromNormal(n);
  vec4 sample_ = vec4(0.0);  // sum of escaping directions, count escaping
  for (uint i = 0u; i < push.rays; ++i) {
    vec3 d = basis * tlSampleCosineHemisphere(tlRandom2(uvec3(uvec2(p), frame.frameIndex * push.rays + i)));
    if (escapes(origin, d)) sample_ += vec4(d, 1.0);
  }
  sample_ /= float(push.rays);
  // The running mean over the history window (an exponential one once it is full).
  vec4 mean = push.frames <= 1u ? sample_ : mix(imageLoad(history, p), sample_, 1.0 / float(push.frames));
  imageStore(history, p, mean);

  float visibility = mean.w;
  vec3 bent = length(mean.xyz) > 1e-6 ? normalize(mean.xyz) : n;
  vec3 irradiance = visibility * tlSkyIrradiance(frame, bent);
  // As SH: a radiance that is the same from every direction and gives this irradiance on the
  // pixel's normal (L1 = 0, E = kShIrradianceL0 x L0): the bent normal's direction is already
  // in the value, so no direction is left for the specular to read (openSkyDirectionality 0).
  vec3 ycocg = tlRgbToYCoCg(irradiance) / kShIrradianceL0;
  ShLumaCoCg sh = tlShFitHalf(tlShMake(vec4(ycocg.x, 0.0, 0.0, 0.0), ycocg.yz));
  imageStore(outShY, p, sh.shY);
  imageStore(outCoCg, p, vec4(sh.coCg, 0.0, 0.0));
  imageStore(outAo, p, vec4(visibility));
}
