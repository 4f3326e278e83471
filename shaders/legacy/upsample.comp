#version 460
// Full resolution from the reduced-resolution SSAO and cone tracing: for each, a depth-aware
// filter over the 2x2 reduced texels around the pixel, with equal spatial weights for the
// SSAO (which averages its 2x2 rotation pattern) and bilinear ones for the cone-traced GI.
// Away from depth edges it reads one gather of view depths and one filtered tap per image
// (depthAwareTaps). AO = SSAO x voxel AO. The SSAO arrives already accumulated over frames
// (legacy.ssao.temporal, at its own resolution). The cone texels' SH were gathered over the
// hemisphere of their own pixel's normal: the filtered SH is divided by the coverage those
// hemispheres give this pixel's normal (shared/sh.h tlShHemisphereCoverage). A pixel whose four
// texels all stand for the sky (a silhouette at reduced resolution) takes the surface texel of
// nearest depth in the 4x4 around them.
#extension GL_GOOGLE_include_directive : require
#include "legacy/legacy_common.glsl"
#include "shared/bilateral.h"
#include "shared/sh.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyUpsampleSsao) uniform sampler2D ssaoIn;  // AO, view depth, frames
layout(set = 0, binding = kLegacyBindingConeShY) uniform sampler2D coneShY;
layout(set = 0, binding = kLegacyBindingConeCoCgAo) uniform sampler2D coneCoCgAo;
layout(set = 0, binding = kLegacyBindingOutAo, r16f) uniform writeonly image2D aoOut;
layout(set = 0, binding = kLegacyBindingOutShY, rgba16f) uniform writeonly image2D shYOut;
layout(set = 0, binding = kLegacyBindingOutCoCg, rg16f) uniform writeonly image2D coCgOut;

float w0;
ivec2 size;

// Weight of a reduced texel from the view depth it stored (0: sky).
float depthWeight(float w) {
  return w <= 0.0 ? 0.0 : tlBilateralWeight(abs(w - w0) / w0, 0.02);
}

// The 2x2 reduced texels whose footprints' centres surround pixel p; at the borders the
// nearest 2x2 inside, so every pixel still averages four different texels (four SSAO rotations).
ivec2 tapBase(ivec2 p, uint d) {
  if (d == 1u) return p;
  ivec2 base = ivec2(floor((vec2(p) + 0.5) / float(d) - 0.5));
  return clamp(base, ivec2(0), max(reducedSize(d) - 2, ivec2(0)));
}

// Four reduced texels around a pixel, in textureGather's order: (0,1), (1,1), (1,0), (0,0)
// from base. Their weights are a spatial weight times the depth weight, normalised. Where
// those weights are (nearly) separable, one bilinear tap at `uv` returns the same weighted
// sum as four fetches: away from depth edges a pass reads one gather (the view depths) and
// one filtered tap per image instead of four fetches per image (lavapipe pays per fetch).
// The images are bound with a linear sampler; texelFetch ignores it.
const ivec2 kGatherOffsets[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));
struct Taps {
  vec4 k;          // normalised weights (all 0: no texel on this surface)
  bool separable;  // k is bilinear at uv within 0.02: one filtered tap will do
  vec2 uv;
  vec4 applied;    // the weights the texels actually get: bilinear at uv when separable, else k
};
Taps depthAwareTaps(vec4 viewDepths, vec4 spatial, ivec2 base, ivec2 reduced) {
  Taps t;
  t.k = vec4(depthWeight(viewDepths.x), depthWeight(viewDepths.y), depthWeight(viewDepths.z), depthWeight(viewDepths.w)) * spatial;
  float sum = t.k.x + t.k.y + t.k.z + t.k.w;
  t.k = sum > 1e-6 ? t.k / sum : vec4(0.0);
  vec2 g = vec2(t.k.y + t.k.z, t.k.x + t.k.y);  // weight on the second column, on the second row
  vec4 err = abs(vec4((1.0 - g.x) * g.y, g.x * g.y, g.x * (1.0 - g.y), (1.0 - g.x) * (1.0 - g.y)) - t.k);
  t.separable = sum > 1e-6 && max(max(err.x, err.y), max(err.z, err.w)) < 0.02;
  t.uv = (vec2(base) + 0.5 + g) / vec2(reduced);
  t.applied = t.separable ? vec4((1.0 - g.x) * g.y, g.x * g.y, g.x * (1.0 - g.y), (1.0 - g.x) * (1.0 - g.y)) : t.k;
  return t;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(aoOut, p, vec4(1.0));
    imageStore(shYOut, p, vec4(0.0));
    imageStore(coCgOut, p, vec4(0.0));
    return;
  }
  w0 = depthToViewW(depth);

  // SSAO: equal spatial weights over the 2x2 texels, which averages the 2x2 rotations.
  float ao = 1.0;
  ivec2 aoSize = reducedSize(push.aoDivisor), aoBase = tapBase(p, push.aoDivisor);
  Taps aoTaps = depthAwareTaps(textureGather(ssaoIn, vec2(aoBase + 1) / vec2(aoSize), 1), vec4(0.25), aoBase, aoSize);
  if (push.aoDivisor == 1u) {
    ao = texelFetch(ssaoIn, p, 0).r;
  } else if (aoTaps.separable) {
    ao = textureLod(ssaoIn, aoTaps.uv, 0.0).r;
  } else if (aoTaps.k != vec4(0.0)) {
    ao = 0.0;
    for (int i = 0; i < 4; ++i) ao += aoTaps.k[i] * texelFetch(ssaoIn, min(aoBase + kGatherOffsets[i], aoSize - 1), 0).r;
  }
  // GI: bilinear spatial weights from where the pixel lies between the four texels.
  vec4 shY = vec4(0.0), coCgAo = vec4(0.0, 0.0, 1.0, 0.0);
  ivec2 giSize = reducedSize(push.coneDivisor);
  vec2 giPos = (vec2(p) + 0.5) / float(push.coneDivisor) - 0.5;  // in reduced texels, centres on integers
  ivec2 giBase = clamp(ivec2(floor(giPos)), ivec2(0), max(giSize - 2, ivec2(0)));
  vec2 f = clamp(giPos - vec2(giBase), vec2(0.0), vec2(1.0));
  vec4 bilinear = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
  vec4 giDepths = textureGather(coneCoCgAo, vec2(giBase + 1) / vec2(giSize), 3);
  Taps giTaps = depthAwareTaps(giDepths, bilinear, giBase, giSize);
  if (giTaps.separable) {
    shY = textureLod(coneShY, giTaps.uv, 0.0);
    coCgAo = textureLod(coneCoCgAo, giTaps.uv, 0.0);
  } else if (giTaps.k != vec4(0.0)) {
    shY = coCgAo = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
      ivec2 q = min(giBase + kGatherOffsets[i], giSize - 1);
      shY += giTaps.k[i] * texelFetch(coneShY, q, 0);
      coCgAo += giTaps.k[i] * texelFetch(coneCoCgAo, q, 0);
    }
  }
  // Normalise by the hemispheres the texels covered (their pixels' normals).
  vec3 n = pixelNormal(p);
  float coverage = 0.0;
  if (giTaps.k == vec4(0.0)) {
    // Every texel around stands for the sky: the nearest surface texel in depth, a ring further.
    float best = 1e30;
    for (int y = -1; y <= 2; ++y)
      for (int x = -1; x <= 2; ++x) {
        ivec2 q = clamp(giBase + ivec2(x, y), ivec2(0), giSize - 1);
        vec4 c = texelFetch(coneCoCgAo, q, 0);
        float rel = abs(c.w - w0) / w0;
        if (c.w <= 0.0 || rel >= best) continue;
        best = rel;
        shY = texelFetch(coneShY, q, 0);
        coCgAo = c;
        coverage = tlShHemisphereCoverage(dot(n, pixelNormal(fullPixel(q, push.coneDivisor))), tlLegacyOpenSkyDirectionality());
      }
  } else {
    // A sky texel holds no light: what weight it still gets (one filtered tap) covers nothing.
    for (int i = 0; i < 4; ++i) {
      if (giDepths[i] <= 0.0) continue;
      vec3 nq = pixelNormal(fullPixel(min(giBase + kGatherOffsets[i], giSize - 1), push.coneDivisor));
      coverage += giTaps.applied[i] * tlShHemisphereCoverage(dot(n, nq), tlLegacyOpenSkyDirectionality());
    }
  }
  if (coverage > 1e-4) shY /= coverage, coCgAo.xy /= coverage;
  float ssao = clamp(ao, 0.0, 1.0);
  float vxao = coCgAo.z;
  imageStore(aoOut, p, vec4(ssao * vxao));
  imageStore(shYOut, p, shY);
  imageStore(coCgOut, p, vec4(coCgAo.xy, 0.0, 0.0));
}
