#version 460
// Ray-traced ambient occlusion as the whole image, by the definition the rt path and the
// reference share: per pixel, cosine-distributed ray queries from the surface; a ray that
// hits within aoRadius is occluded, and the visibility is the share that is not. Running mean
// while the view holds still. Grey = visibility (white unoccluded), black on the sky, so the
// radiance the composite passes through is the AO itself (EXR captures hold its values).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/sampling.h"
#include "ao_debug.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kAoDebugNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kAoDebugDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kAoDebugTlas) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = kAoDebugHistory, r32f) uniform image2D history;
layout(set = 0, binding = kAoDebugOutput, rgba32f) uniform writeonly image2D outGrey;
layout(push_constant) uniform Push { AoDebugPush push; };

#include "common/camera.glsl"

bool unoccluded(vec3 origin, vec3 direction) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xFF, origin, 0.0, direction,
                        push.aoRadius);
  while (rayQueryProceedEXT(q)) {}
  return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: black, nothing to occlude
    imageStore(history, p, vec4(0.0));
    imageStore(outGrey, p, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 origin = tlOffsetRayOrigin(pixelPosition(p, depth), n, frame.sceneScale);
  mat3 basis = tlBasisFromNormal(n);
  float open = 0.0;
  for (uint i = 0u; i < push.rays; ++i) {
    vec3 d = basis * tlSampleCosineHemisphere(tlRandom2(uvec3(uvec2(p), frame.frameIndex * push.rays + i)));
    if (unoccluded(origin, d)) open += 1.0;
  }
  float sample_ = open / float(push.rays);
  // The running mean over the history window (an exponential one once it is full).
  float visibility = push.frames <= 1u ? sample_ : mix(imageLoad(history, p).r, sample_, 1.0 / float(push.frames));
  imageStore(history, p, vec4(visibility));
  imageStore(outGrey, p, vec4(vec3(visibility), 1.0));
}
