#version 460
// Writes the voxel under the fragment: opacity 1, and the diffuse radiance the surface sends
// out of each side (sun through the shadow map + emission), into the anisotropic faces that
// side faces (shared/legacy.h). Direct light is injected here, while the surface is at hand.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/legacy.h"
#include "shared/rt.h"
#include "shared/sampling.h"
#include "shared/scene.h"

layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingShadow) uniform sampler2DShadow sunShadow;
layout(set = 0, binding = kLegacyBindingRadiance, rgba16f) uniform writeonly image3D radianceOut;
layout(set = 0, binding = kLegacyBindingSeeds, r8ui) uniform writeonly uimage3D seedsOut;
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
#include "common/material.glsl"
layout(set = 0, binding = kLegacyBindingPrevRadiance) uniform sampler2D previousRadiance;
layout(set = 0, binding = kLegacyBindingPrevDepth) uniform sampler2D previousDepth;
layout(push_constant) uniform Push { LegacyVoxelPush push; };

#include "common/camera.glsl"

// The radiance last frame's image showed at this point, if the point was on screen and
// unoccluded then: it holds every light and every bounce so far, so feeding it back into
// the voxels makes the GI multi-bounce over frames (the RT path does the same at its hits).
bool screenRadiance(vec3 position, vec3 normal, out vec3 radiance) {
  radiance = vec3(0.0);
  if (push.screenRadiance == 0u || dot(normal, towardsViewer(position)) <= 0.0) return false;
  vec4 clip = frame.prevViewProj * vec4(position, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
  float depth = textureLod(previousDepth, uv, 0.0).r;
  if (depth <= 0.0) return false;
  float seenW = depthToViewW(depth);
  float pointW = viewWOfClip(clip);
  if (abs(seenW - pointW) > 0.03 * pointW + 2.0 * push.clipmap.levelMin[push.axis / 3u].w) return false;
  radiance = textureLod(previousRadiance, uv, 0.0).rgb;
  return true;
}

#include "common/sun_shadow.glsl"

// The light table (shared/lights.h) injected like the sun: point and spot lights through their
// shadow maps (common/light_shadow.glsl; frames without maps bind stand-ins, never read since
// no light then names a view), the rest unshadowed.
vec3 gLightPosition, gLightNormal, gLightAlbedo;
float lightVisibility(uint light, vec3 toLight, float distance);
vec3 lightResponse(vec3 toLight) { return gLightAlbedo * (kInvPi * max(dot(gLightNormal, toLight), 0.0)); }
#include "common/lights.glsl"
#include "common/light_shadow.glsl"
float lightVisibility(uint light, vec3 toLight, float distance) { return lightShadowVisibility(light, gLightPosition, gLightNormal); }

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inInstance;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;

const vec3 kFace[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));

void main() {
  uint level = push.axis / 3u;
  int R = int(push.clipmap.resolution);
  vec4 box = push.clipmap.levelMin[level];
  ivec3 v = ivec3(floor((inPosition - box.xyz) / box.w));
  if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(R)))) return;
  // A partial update cleared only its region: voxels outside it keep what they hold, and the
  // scissor bounds only the two raster axes, not depth.
  if (any(lessThan(v, push.regionMin.xyz)) || any(greaterThanEqual(v, push.regionMax.xyz))) return;
  GpuMaterial m = materials[instances[inInstance].material];
  vec4 base = materialBaseColor(m, inUv, inUv1, inColor);
  // A translucent (BLEND) surface fills alpha of its voxels: an ordered dither over the voxel
  // grid (the (x + y, z + 3y) mix keeps every 4x4 block of an axis-aligned wall exact); the
  // cone tracer's mips average it to an opacity of alpha. Both rounds decide alike.
  // A transmitting surface fills the voxels its coverage says (shared/scene.h), the same way.
  float coverage = materialCoverage(m, inUv, inUv1, base.rgb);
  if (materialCutoutTransmitting(m, base.a, coverage, tlOrderedDither4(uint(v.x + v.y), uint(v.z + 3 * v.y)))) return;
  vec3 emission = materialEmission(m, inUv, inUv1);
  vec3 albedo = tlMaterialHitAlbedo(clamp(base.rgb, 0.0, 1.0), m.metallic, tlFrameMaterials(frame.flags));
  vec3 n = normalize(inNormal);
  ivec3 z = ivec3(0, 0, int(level) * R);
  // Round 0: the voxel is solid from every side (rgb 0, opacity 1). Round 1, after a barrier:
  // each side of the surface (a single quad is a wall seen from either side) writes the faces
  // it looks out of (n.face > 0.35) with its radiance. A wall's two sides fill opposite faces
  // of the same voxel, so its lit side cannot shine out of the other one.
  if (push.voxelRound == 0u) {
    for (int f = 0; f < 6; ++f) imageStore(radianceOut, ivec3(v.x + f * R, v.y, v.z) + z, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  for (int side = 0; side < 2; ++side) {
    vec3 ns = side == 0 ? n : -n;
    float nl = dot(ns, frame.sunToLight.xyz);
    vec3 radiance = emission;
    if (nl > 0.0) radiance += albedo * kInvPi * frame.sunIrradiance.rgb * (nl * sunVisibility(inPosition, ns));
    if (frame.lightCount > 0u) {
      gLightPosition = inPosition;
      gLightNormal = ns;
      gLightAlbedo = albedo;
      radiance += shadeLights(inPosition, ns, uvec3(uvec2(v.xy), uint(v.z) + 977u * uint(side)));
    }
    // Direct light (not last frame's image, which may hold light that leaked) marks the
    // empty voxels this side looks into as where light enters the air (the rooms' seeds).
    bool lit = any(greaterThan(radiance, vec3(0.0)));
    vec3 seen;
    if (screenRadiance(inPosition, ns, seen)) radiance = seen;
    for (int f = 0; f < 6; ++f) {
      if (dot(ns, kFace[f]) <= 0.35) continue;
      imageStore(radianceOut, ivec3(v.x + f * R, v.y, v.z) + z, vec4(radiance, 1.0));
      ivec3 front = v + ivec3(kFace[f]);
      if (lit && level == 0u && push.clipmap.roomGate != 0u && all(greaterThanEqual(front, ivec3(0))) && all(lessThan(front, ivec3(R))))
        imageStore(seedsOut, front, uvec4(1u));
    }
  }
}
