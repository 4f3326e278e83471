#version 460
// shadow.sun.hybrid: the sun's visibility per pixel from hybrid ray-traced shadows (GameWorks
// HRTS): one ray query towards the sun's centre gives the exact hard shadow, PCSS over the shadow
// map the soft one, and the blocker distance blends them. Near a contact the true penumbra is
// narrower than the map can draw (and the map's bias lifts the shadow off the contact), so
// the ray decides; far from it the penumbra is wide and the map's filter is right. The
// composite uses the result instead of its own PCSS lookup.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#include "shared/frame.h"
#include "shared/hybrid_shadow.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kHybridShadowNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kHybridShadowDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kHybridShadowMap) uniform sampler2DShadow sunShadow;
layout(set = 0, binding = kHybridShadowTlas) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = kHybridShadowOutput, r16f) uniform writeonly image2D outVisibility;
layout(push_constant) uniform Push { HybridShadowPush push; };

#include "common/camera.glsl"

#define TL_SUN_SHADOW_PCSS
layout(set = 0, binding = kHybridShadowMapDepth) uniform sampler2D sunShadowDepth;
#include "common/sun_shadow.glsl"

// The distance to the nearest surface between the surface and the sun's centre, or -1 when
// nothing lies there (the closest hit, not the first found: it bounds the penumbra below).
float tracedBlocker(vec3 origin, vec3 toSun) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsOpaqueEXT, 0xFF, origin, 0.0, toSun, 1e30);
  while (rayQueryProceedEXT(q)) {}
  return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionNoneEXT
             ? -1.0
             : rayQueryGetIntersectionTEXT(q, true);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: nothing to shadow
    imageStore(outVisibility, p, vec4(1.0));
    return;
  }
  vec3 position = pixelPosition(p, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  vec3 l = frame.sunToLight.xyz;
  if (dot(n, l) <= 0.0 || (frame.flags & kFrameFlagSunShadows) == 0u) {
    // Facing away the sun adds nothing; without a sun shadow there is no sun.
    imageStore(outVisibility, p, vec4(dot(n, l) > 0.0 ? 1.0 : 0.0));
    return;
  }
  SunShadowEstimate soft = sunShadowSoft(position, n, p);
  float blocker = tracedBlocker(tlOffsetRayOrigin(position, n, frame.sceneScale), l);
  float traced = blocker < 0.0 ? 1.0 : 0.0;
  float hard = max(push.hardPenumbraTexels * frame.shadowParams.x, 1e-6);
  float visibility;
  if (soft.blockerDistance < 0.0) {
    // The map saw no blocker; a ray that hits found one the map cannot (thinner than a texel,
    // outside the map's fit): the ray's answer either way.
    visibility = traced;
  } else {
    // L = saturate(penumbra width / the narrowest the map draws); the talk's lerp(RTS, PCSS, L).
    // Where the ray is blocked, its own (nearest) blocker bounds how wide the penumbra can be:
    // a wall close by that the map's texels let light past (a corner of sides without
    // thickness) still shadows, as the ray says.
    float blockerDistance = blocker < 0.0 ? soft.blockerDistance : min(soft.blockerDistance, blocker);
    float penumbra = 2.0 * tan(frame.sunToLight.w) * blockerDistance;
    visibility = mix(traced, soft.visibility, clamp(penumbra / hard, 0.0, 1.0));
  }
  imageStore(outVisibility, p, vec4(visibility));
}
