#version 460
// One pass of the RT path's spatial denoiser on the SH irradiance (Metro Exodus, "little
// monster"): 3x3 variance of the input; radius = base * F(viewZ) * F(variance) * F(AO) (the
// world radius projected at this depth, shrunk where the signal is already clean and in dark
// corners); an adaptive step through a 16-tap Poisson disk (small radius, fewer taps) rotated
// per frame, not per pixel; a step-function weight on the distance to the centre's tangent
// plane (absolute, so rounded objects are not skipped); pass 2 adds a linear normal weight.
// Taps of other normals are normalised by the hemisphere each covers at this pixel's normal
// (shared/sh.h tlShHemisphereCoverage), so the light they never sampled is not lost. The
// output keeps part of the input: lerp(denoised, input, 0.5 * accumulation speed).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/rt.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kRtBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kRtBindingNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kRtBindingShY) uniform sampler2D inShY;
layout(set = 0, binding = kRtBindingCoCg) uniform sampler2D inCoCgAo;
layout(set = 0, binding = kRtBindingDenoiseShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kRtBindingDenoiseCoCgAo, rgba16f) uniform writeonly image2D outCoCgAo;
layout(push_constant) uniform Push { RtDenoisePush push; };

const vec2 kDisk[16] = vec2[16](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

#include "common/camera.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 shY0 = texelFetch(inShY, p, 0);
  vec4 coCgAo0 = texelFetch(inCoCgAo, p, 0);
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(outShY, p, shY0);
    imageStore(outCoCgAo, p, coCgAo0);
    return;
  }
  vec3 P0 = pixelPosition(p, depth);
  vec3 n0 = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  float w0 = depthToViewW(depth);

  // 3x3 relative standard deviation of the luma band.
  float sum = 0.0, sum2 = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      float l = texelFetch(inShY, clamp(p + ivec2(x, y), ivec2(0), size - 1), 0).x;
      sum += l;
      sum2 += l * l;
    }
  float mean = sum / 9.0;
  float sigma = sqrt(max(sum2 / 9.0 - mean * mean, 0.0));
  float fVariance = clamp(2.0 * sigma / max(abs(mean), 1e-4), 0.1, 1.0);
  float fAo = mix(0.5, 1.0, clamp(coCgAo0.z, 0.0, 1.0));
  float radius = clamp(push.baseRadius * fVariance * fAo / pixelFootprint(w0), 1.0, 48.0);
  int step = radius < 4.0 ? 4 : (radius < 8.0 ? 2 : 1);

  float c = cos(push.rotation), s = sin(push.rotation);
  mat2 rotation = mat2(c, s, -s, c);
  vec4 shY = shY0;
  vec2 coCg = coCgAo0.xy;
  float coverage = 1.0;
  float plane = push.planeDistance * w0;
  for (int i = 0; i < 16; i += step) {
    ivec2 q = p + ivec2(round(rotation * kDisk[i] * radius));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) || q == p) continue;
    float d = texelFetch(gDepth, q, 0).r;
    if (d <= 0.0) continue;
    if (abs(dot(n0, pixelPosition(q, d) - P0)) > plane) continue;  // off the tangent plane: weight 0
    float cosNormals = dot(n0, tlOctDecode(texelFetch(gNormal, q, 0).xy));
    float k = push.normalWeight != 0u ? max(cosNormals, 0.0) : 1.0;
    if (k <= 0.0) continue;
    shY += k * texelFetch(inShY, q, 0);
    coCg += k * texelFetch(inCoCgAo, q, 0).xy;
    coverage += k * tlShHemisphereCoverage(cosNormals, kShOpenSkyDirectionality);
  }
  // Over the covered irradiance rather than the weights (the centre covers itself: 1). The
  // chroma is a ratio to the luma's L0, so it is divided alike.
  shY /= coverage;
  coCg /= coverage;
  // Accumulation speed: 0 for a fresh pixel (all denoised), towards 1 once history is long.
  float accumulation = 1.0 - 1.0 / max(coCgAo0.w, 1.0);
  float keep = 0.5 * accumulation;
  imageStore(outShY, p, mix(shY, shY0, keep));
  imageStore(outCoCgAo, p, vec4(mix(coCg, coCgAo0.xy, keep), coCgAo0.zw));
}
