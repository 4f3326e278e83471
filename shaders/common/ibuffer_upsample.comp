#version 460
// ibuffer.upsample (redeferredRate below 1): ibuffer.filled.*, the I-buffer with the pixels the
// pattern did not shade filled from the shaded ones around them (3x3) with depth- and normal-aware weights, the
// diffuse sums (Ldg, Lms) and the specular ones (Lsg1, Lsg2) each with their own weights. A
// pixel is left for the illumination passes' refining run (ibuffer.refine = kIbufferRefined)
// instead where a filled value would cross an edge: a shaded neighbour on another surface
// (off this pixel's tangent plane, another normal or roughness, the sky) or neighbours whose
// light disagrees (a shadow's edge, a lamp's falloff, a highlight), so full rate is kept there.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/bilateral.h"
#include "shared/packing.h"
#include "shared/redeferred.h"
#include "shared/shading.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kIbufferNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kIbufferMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kIbufferDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kIbufferSumDg) uniform sampler2D shadedDg;  // ibuffer.shaded.*: the pattern's pixels
layout(set = 0, binding = kIbufferSumSg1) uniform sampler2D shadedSg1;
layout(set = 0, binding = kIbufferSumSg2) uniform sampler2D shadedSg2;
layout(set = 0, binding = kIbufferSumMs) uniform sampler2D shadedMs;
layout(set = 0, binding = kIbufferOutDg, rgba32f) uniform writeonly image2D ioDg;  // ibuffer.filled.*
layout(set = 0, binding = kIbufferOutSg1, rgba32f) uniform writeonly image2D ioSg1;
layout(set = 0, binding = kIbufferOutSg2, rgba32f) uniform writeonly image2D ioSg2;
layout(set = 0, binding = kIbufferOutMs, rgba32f) uniform writeonly image2D ioMs;
layout(set = 0, binding = kIbufferRefineMask, r32f) uniform writeonly image2D refineMask;
layout(push_constant) uniform Push { IbufferUpsamplePush push; };

#include "common/camera.glsl"

void store(ivec2 p, IbufferSums s, float mark) {
  imageStore(ioDg, p, vec4(s.dg, 1.0));
  imageStore(ioSg1, p, vec4(s.sg1, 1.0));
  imageStore(ioSg2, p, vec4(s.sg2, 1.0));
  imageStore(ioMs, p, vec4(s.ms, 1.0));
  imageStore(refineMask, p, vec4(mark));
}

IbufferSums shadedAt(ivec2 q) {
  IbufferSums s;
  s.dg = texelFetch(shadedDg, q, 0).rgb;
  s.sg1 = texelFetch(shadedSg1, q, 0).rgb;
  s.sg2 = texelFetch(shadedSg2, q, 0).rgb;
  s.ms = texelFetch(shadedMs, q, 0).rgb;
  return s;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  if (tlIbufferShadedFirst(p, push.pattern)) {
    store(p, shadedAt(p), kIbufferShadedFirst);
    return;
  }
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {  // the sky: nothing to light
    store(p, tlIbufferZero(), kIbufferShadedFirst);
    return;
  }
  uint materials = tlFrameMaterials(frame.flags);
  vec3 position = pixelPosition(p, depth);
  float distance = length(position);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  float roughness = tlMaterialRoughness(texelFetch(gMaterial, p, 0).x, materials);

  IbufferSums sum = tlIbufferZero();
  float diffuseWeight = 0.0, specularWeight = 0.0;
  bool edge = false;
  float lo[2] = float[2](1e30, 1e30), hi[2] = float[2](0.0, 0.0);  // luminance range: diffuse, specular
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = p + ivec2(x, y);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) || !tlIbufferShadedFirst(q, push.pattern)) continue;
      float dq = texelFetch(gDepth, q, 0).r;
      if (dq <= 0.0) {  // a silhouette against the sky
        edge = true;
        continue;
      }
      // Geometry: distance off this pixel's tangent plane (relative to its distance), normal, roughness.
      float plane = abs(dot(n, pixelPosition(q, dq) - position)) / distance;
      float cosine = dot(n, tlOctDecode(texelFetch(gNormal, q, 0).xy));
      float dr = abs(tlMaterialRoughness(texelFetch(gMaterial, q, 0).x, materials) - roughness);
      edge = edge || plane > kIbufferEdgePlane || cosine < kIbufferEdgeCosine || dr > kIbufferEdgeRoughness;
      IbufferSums s = shadedAt(q);
      float ld = tlLuminance(s.dg), ls = tlLuminance(s.sg1);
      lo[0] = min(lo[0], ld), hi[0] = max(hi[0], ld);
      lo[1] = min(lo[1], ls), hi[1] = max(hi[1], ls);
      // The weights: nearer neighbours more (the diagonal ones half), the same surface more.
      float spatial = (x == 0 || y == 0) ? 1.0 : 0.5;
      float geometry = spatial * tlBilateralWeight(plane, kIbufferEdgePlane);
      float wd = geometry * pow(max(cosine, 0.0), kIbufferDiffuseNormalPower);
      float ws = geometry * pow(max(cosine, 0.0), kIbufferSpecularNormalPower) * tlBilateralWeight(dr, kIbufferEdgeRoughness);
      sum.dg += wd * s.dg;
      sum.ms += wd * s.ms;
      sum.sg1 += ws * s.sg1;
      sum.sg2 += ws * s.sg2;
      diffuseWeight += wd;
      specularWeight += ws;
    }
  // The light: neighbours whose sums differ by more than kIbufferEdgeLight of the largest.
  for (int i = 0; i < 2; ++i) edge = edge || (hi[i] > kIbufferLightFloor && hi[i] - lo[i] > kIbufferEdgeLight * hi[i]);
  if (edge || !(diffuseWeight > 0.0) || !(specularWeight > 0.0)) {
    store(p, tlIbufferZero(), kIbufferRefined);  // the refining run shades it
    return;
  }
  sum.dg /= diffuseWeight;
  sum.ms /= diffuseWeight;
  sum.sg1 /= specularWeight;
  sum.sg2 /= specularWeight;
  store(p, sum, kIbufferFilled);
}
