#version 460
// Disocclusion rays into the accumulation (shared/rt.h): a pixel without history takes the
// cells around it (bilinear over the 8x8 grid) whose rays left from its own plane, as
// tlRtDisocclusionFrames of history beside its one sample. Pixels with history pass through.
#extension GL_GOOGLE_include_directive : require
#include "rt/rt_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBlendAccumulatedShY) uniform sampler2D accumulatedShY;
layout(set = 0, binding = kRtBlendAccumulatedCoCgAo) uniform sampler2D accumulatedCoCgAo;
layout(set = 0, binding = kRtBlendCellShY) uniform sampler2D cellShY;
layout(set = 0, binding = kRtBlendCellCoCgAo) uniform sampler2D cellCoCgAo;
layout(set = 0, binding = kRtBlendCellOrigin) uniform sampler2D cellPosition;
layout(set = 0, binding = kRtBlendOutShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kRtBlendOutCoCgAo, rgba16f) uniform writeonly image2D outCoCgAo;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 shY = texelFetch(accumulatedShY, p, 0);
  vec4 coCgAo = texelFetch(accumulatedCoCgAo, p, 0);
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth > 0.0 && coCgAo.w <= kRtDisocclusionFreshFrames) {
    vec3 position = pixelPosition(p, depth);
    vec3 n = pixelNormal(p);
    float tolerance = 0.02 * viewW(position);  // as the denoiser's plane distance
    ivec2 cells = textureSize(cellPosition, 0);
    vec2 c = (vec2(p) + 0.5) / float(kRtDisocclusionCell) - 0.5;
    ivec2 base = ivec2(floor(c));
    vec2 f = c - vec2(base);
    vec4 sumShY = vec4(0.0), sumCoCgAo = vec4(0.0);
    float total = 0.0, bilinear = 0.0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        ivec2 q = clamp(base + ivec2(i, j), ivec2(0), cells - 1);
        float b = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
        bilinear += b;
        vec4 from = texelFetch(cellPosition, q, 0);
        if (from.w <= 0.0) continue;  // nothing traced there
        vec4 s = texelFetch(cellShY, q, 0), a = texelFetch(cellCoCgAo, q, 0);
        if (!finite4(s) || !finite4(a)) continue;
        float plane = abs(dot(n, from.xyz - position)) / tolerance;
        float w = b / (1.0 + plane * plane);
        sumShY += w * s;
        sumCoCgAo += w * a;
        total += w;
      }
    if (total > 1e-4) {
      // How much of the pixel's bilinear footprint is on its plane: the prior's confidence.
      float prior = tlRtDisocclusionFrames(push.disocclusionRays) * total / max(bilinear, 1e-6);
      float frames = max(coCgAo.w, 0.0);
      float k = prior / (frames + prior);
      shY = mix(shY, sumShY / total, k);
      // At least one frame's weight: the accumulation keeps a history only from one frame up.
      coCgAo = vec4(mix(coCgAo.xyz, sumCoCgAo.xyz / total, k), max(frames + prior, 1.0));
    }
  }
  imageStore(outShY, p, shY);
  imageStore(outCoCgAo, p, coCgAo);
}
