#version 460
// The legacy path's reflections (shared/legacy_reflections.h): no ray tracing, the RT path's
// contract. A pixel below the roughness threshold follows its mirror direction twice:
//  - across the screen, through the hierarchical depth (a march that skips whole cells the ray
//    passes in front of, and looks closer where it may not): a surface that was on screen last
//    frame gives that frame's light (screen-space reflections);
//  - through the voxel clipmap, as a cone whose aperture follows the lobe's width (VXGI's
//    specular cone): what it gathers, and the sky beyond it.
// The march's confidence blends them: it fades at the screen's edges, is 0 where the march
// found nothing or a surface last frame did not show, follows the diffuse share of what it met
// (last frame's image holds the light sent towards the camera, not towards this pixel), and
// falls as the lobe widens (one mirror ray stands for less of a rough lobe, whose blur the
// cone has).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/legacy_reflections.h"
#include "shared/packing.h"
#include "shared/shading.h"
#include "shared/rt_specular.h"
#include "shared/bilateral.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLegacyBindingNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kLegacyBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kLegacyBindingBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kLegacyBindingHiz) uniform sampler2D hiz;
layout(set = 0, binding = kLegacyBindingPrevRadiance) uniform sampler2D previousRadiance;  // when screenHistory
layout(set = 0, binding = kLegacyBindingPrevDepth) uniform sampler2D previousDepth;        // when screenHistory
layout(set = 0, binding = kLegacyBindingReflections, rgba16f) uniform writeonly image2D reflectionsOut;
layout(set = 0, binding = kLegacyBindingReflectionsReduced) uniform sampler2D reducedIn;  // kLegacyReflectionsUpsample
layout(push_constant) uniform Push { LegacyReflectionPush push; };

#include "common/camera.glsl"
#include "legacy/voxel_cones.glsl"

vec3 pixelNormal(ivec2 p) { return tlOctDecode(texelFetch(gNormal, p, 0).xy); }

// The screen-space march along `dir` from `position` (pixel `p`): the confidence in what it
// found (0: nothing usable) and, where above 0, last frame's light from the surface it met.
float screenSpaceReflection(vec3 position, vec3 dir, out vec3 radiance) {
  radiance = vec3(0.0);
  vec2 viewport = frame.viewport.xy;
  // The ray's far end: the scene's size away (the coarsest clipmap level spans the scene),
  // pulled in to stay in front of a perspective camera's near plane.
  LegacyClipmap c = push.clipmap;
  float len = c.levelMin[c.levels - 1u].w * float(c.resolution);
  vec4 clip0 = frame.viewProj * vec4(position, 1.0);
  vec4 clipDir = frame.viewProj * vec4(dir, 0.0);
  if (!cameraOrthographic()) {
    float nearW = 1.01 * frame.proj[3][2];  // reversed Z: depth = near / w
    if (clip0.w + clipDir.w * len < nearW) len = (nearW - clip0.w) / clipDir.w;  // clipDir.w < 0 here
    if (!(len > 0.0)) return 0.0;
  }
  vec4 clip1 = clip0 + clipDir * len;
  // Screen position (pixels) and depth: a line in space is a line in this space too.
  vec3 s0 = vec3((clip0.xy / clip0.w * 0.5 + 0.5) * viewport, clip0.z / clip0.w);
  vec3 s1 = vec3((clip1.xy / clip1.w * 0.5 + 0.5) * viewport, clip1.z / clip1.w);
  vec3 d = s1 - s0;
  float pixels = length(d.xy);
  if (pixels < 1.0) return 0.0;  // along the view axis: the screen shows nothing of it
  float tEnd = 1.0;
  for (int a = 0; a < 2; ++a) {
    if (d[a] > 0.0) tEnd = min(tEnd, (viewport[a] - s0[a]) / d[a]);
    if (d[a] < 0.0) tEnd = min(tEnd, -s0[a] / d[a]);
  }
  const float nudge = 1e-3 / pixels;  // a thousandth of a pixel: into the next cell
  int maxLevel = int(push.hizMips) - 1;
  int level = 0;
  float t = 1.0 / pixels;  // a pixel away from the start
  bool hit = false;
  ivec2 cell = ivec2(0);
  for (uint i = 0u; i < push.maxSteps && t < tEnd; ++i) {
    vec2 at = s0.xy + d.xy * t;
    float size = float(1 << level);
    cell = ivec2(floor(at / size));
    vec2 boundary = (vec2(cell) + step(vec2(0.0), d.xy)) * size;
    vec2 exits = vec2(d.x != 0.0 ? (boundary.x - s0.x) / d.x : 1e30, d.y != 0.0 ? (boundary.y - s0.y) / d.y : 1e30);
    float tExit = min(min(exits.x, exits.y), tEnd);
    // Reversed Z: larger is nearer. Past a mip's last texel, that texel bounds the rest (hiz_reduce.comp).
    float nearest = texelFetch(hiz, clamp(cell, ivec2(0), textureSize(hiz, level) - 1), level).r;
    float zEnter = s0.z + d.z * t, zExit = s0.z + d.z * tExit;
    if (min(zEnter, zExit) > nearest) {  // in front of everything in the cell: skip it, look wider
      t = tExit + nudge;
      level = min(level + 1, maxLevel);
      continue;
    }
    if (level > 0) {  // it may meet something here: move up to the cell's nearest depth, look closer
      if (d.z < 0.0 && zEnter > nearest) t = min(t + (zEnter - nearest) / -d.z, tExit);
      --level;
      continue;
    }
    // One pixel. The ray crosses its surface here, or runs behind it: within a thickness of
    // 2% of the view distance that is a hit (the depth buffer holds fronts only), else the ray
    // passes behind an object and goes on.
    float wSurface = depthToViewW(nearest);
    float wRay = depthToViewW(max(max(zEnter, zExit), 1e-30));
    if (max(zEnter, zExit) >= nearest || wRay - wSurface <= 0.02 * wSurface) {
      hit = true;
      break;
    }
    t = tExit + nudge;
  }
  if (!hit) return 0.0;
  cell = clamp(cell, ivec2(0), ivec2(viewport) - 1);
  // The surface met must face the ray, and must have been on screen last frame.
  float hitDepth = texelFetch(gDepth, cell, 0).r;
  if (hitDepth <= 0.0 || dot(pixelNormal(cell), dir) >= 0.0) return 0.0;
  vec3 hitPosition = pixelPosition(cell, hitDepth);
  vec4 previous = frame.prevViewProj * vec4(hitPosition, 1.0);
  if (previous.w <= 0.0) return 0.0;
  vec2 uv = previous.xy / previous.w * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 0.0;
  float seenW = depthToViewW(max(textureLod(previousDepth, uv, 0.0).r, 1e-30));
  float expectedW = viewWOfClip(previous);
  if (abs(seenW - expectedW) > 0.02 * expectedW) return 0.0;
  radiance = textureLod(previousRadiance, uv, 0.0).rgb;
  if (!all(lessThan(abs(radiance), vec3(1e30)))) return 0.0;
  // Last frame's pixel is the light the surface sent towards the camera; towards this pixel it
  // sends the same only in its diffuse share (a metal's highlight is somewhere else seen from
  // here): the march is trusted in proportion to that share of the surface's albedo.
  SurfaceParams met = tlGbufferSurface(texelFetch(gBaseColor, cell, 0), texelFetch(gMaterial, cell, 0), tlFrameMaterials(frame.flags));
  float diffuse = tlLuminance(met.diffuse * (vec3(1.0) - met.layerAverage));
  float whole = tlLuminance(tlHemisphericalAlbedo(met));
  float viewIndependent = whole > 0.0 ? clamp(diffuse / whole, 0.0, 1.0) : 1.0;
  // Fade over the outer tenth of the screen, where the next frame may lose what it shows.
  vec2 edge = min(uv, 1.0 - uv) / 0.1;
  return clamp(min(edge.x, edge.y), 0.0, 1.0) * viewIndependent;
}

// The specular cone along `dir`: a GGX lobe of width alpha sends its reflections over about
// tan(theta) = alpha around the mirror direction (at least a voxel wide: marchCone).
vec3 coneRadiance(vec3 position, vec3 n, vec3 dir, float alpha) {
  float voxel = push.clipmap.levelMin[0].w;
  vec3 origin = position + n * (1.5 * voxel);  // leave the surface's own voxel
  if (!lightReaches(origin)) return vec3(0.0);
  ConeMarch cone = marchCone(origin, n, dir, alpha, push.coneRange, 0.99, 0.0);
  return cone.gathered + (1.0 - cone.occlusion) * tlSkyRadiance(frame, dir);
}

// Whether pixel p reflects (a surface below the roughness threshold whose lobe reflects
// something) and its weight against the SH specular.
bool reflects(ivec2 p, out SurfaceParams s, out float weight) {
  weight = 0.0;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) return false;
  s = tlGbufferSurface(texelFetch(gBaseColor, p, 0), texelFetch(gMaterial, p, 0), tlFrameMaterials(frame.flags));
  weight = tlRtSpecularTracedWeight(s.roughness, push.roughness);
  vec3 n = pixelNormal(p);
  vec3 v = tlSamplingView(n, towardsViewer(pixelPosition(p, depth)));
  vec2 split = tlSpecularAlbedoSplit(max(dot(n, v), kBrdfMinCosine), s.roughness);
  return s.specular > 0.0 && weight > 0.0 && tlRtSpecularWorthTracing(s.f0 * split.x + s.f90 * split.y);
}

// What pixel p, whose surface s reflects (reflects), reflects: the march and the cone's radiance
// (rgb) and its weight against the SH specular (a).
vec4 marched(ivec2 p, SurfaceParams s, float weight) {
  vec3 position = pixelPosition(p, texelFetch(gDepth, p, 0).r);
  vec3 n = pixelNormal(p);
  vec3 dir = reflect(-tlSamplingView(n, towardsViewer(position)), n);
  vec3 screen = vec3(0.0);
  float confidence = 0.0;
  if (push.screenHistory != 0u && push.maxSteps > 0u) {
    confidence = screenSpaceReflection(position, dir, screen);
    confidence *= 1.0 - clamp(s.roughness / push.roughness, 0.0, 1.0);
  }
  vec3 radiance = confidence * screen;
  if (confidence < 1.0) radiance += (1.0 - confidence) * coneRadiance(position, n, dir, s.alpha);
  return vec4(min(radiance, vec3(65000.0)), weight);
}

// The same for any pixel (a = 0 and rgb 0 where it reflects nothing).
vec4 reflection(ivec2 p) {
  SurfaceParams s;
  float weight;
  return reflects(p, s, weight) ? marched(p, s, weight) : vec4(0.0);
}

// The reduced texels around pixel p on p's own surface, bilinear: their weighted mean (rgb) and
// the share of the bilinear weight on p's surface (a). Reduced texel t stands for pixel 2t; it
// counts where that pixel has p's material (the G-buffer's roughness, metalness and F0 within
// its 8-bit steps: a puddle's reflection never spreads onto the asphalt around it), and weighs
// less as its view depth and normal differ from p's.
vec4 upsampled(ivec2 p) {
  vec3 n = pixelNormal(p);
  vec3 material = texelFetch(gMaterial, p, 0).rgb;
  float w0 = depthToViewW(texelFetch(gDepth, p, 0).r);
  ivec2 reduced = textureSize(reducedIn, 0);
  vec2 at = vec2(p) * 0.5;  // p in reduced texels' coordinates (texel t at pixel 2t)
  ivec2 base = ivec2(floor(at));
  vec2 f = at - vec2(base);
  vec4 sum = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 t = min(base + o, reduced - 1);
    vec4 texel = texelFetch(reducedIn, t, 0);
    if (texel.a <= 0.0) continue;  // nothing was reflected there
    ivec2 q = min(2 * t, ivec2(frame.viewport.xy) - 1);
    if (any(greaterThan(abs(texelFetch(gMaterial, q, 0).rgb - material), vec3(1.5 / 255.0)))) continue;
    float w = depthToViewW(texelFetch(gDepth, q, 0).r);
    float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    float weight = bilinear * tlBilateralWeight(abs(w - w0) / w0, 0.02) * pow(max(dot(pixelNormal(q), n), 0.0), 32.0);
    sum += vec4(texel.rgb * weight, weight);
  }
  return sum.a > 0.0 ? vec4(sum.rgb / sum.a, sum.a) : vec4(0.0);
}

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (push.mode == kLegacyReflectionsReduced) {
    ivec2 p = 2 * id;
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    vec4 r = reflection(p);
    imageStore(reflectionsOut, id, vec4(r.rgb, r.a > 0.0 ? 1.0 : 0.0));
    return;
  }
  ivec2 p = id;
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  if (push.mode != kLegacyReflectionsUpsample) {
    imageStore(reflectionsOut, p, reflection(p));
    return;
  }
  SurfaceParams s;
  float weight;
  if (!reflects(p, s, weight)) {
    imageStore(reflectionsOut, p, vec4(0.0));
    return;
  }
  // The G-buffer's roughness, not the BRDF's floored one.
  if (texelFetch(gMaterial, p, 0).r > push.fullRoughness) {
    vec4 u = upsampled(p);
    // A pixel the reduced texels hardly stand for (less than a quarter of the bilinear weight
    // on its surface: an edge, a small object) is marched itself.
    if (u.a >= 0.25) {
      imageStore(reflectionsOut, p, vec4(u.rgb, weight));
      return;
    }
  }
  imageStore(reflectionsOut, p, marched(p, s, weight));
}
