#version 460
// The reflections' spatial filter (shared/rt_specular.h), sized by the lobe, not by the diffuse
// denoiser's room-scale radius: a reflection seen through a GGX lobe is blurred over about
// hit distance x alpha on the surface (RE ENGINE: small scale for smooth, large for rough), so
// the footprint is that many pixels at this depth, shrunk by the square root of the frames
// accumulated (the history already averages that many samples) and capped at
// RtSpecularPush::maxRadius. The mirror path is not filtered (RE ENGINE's mirrors). Taps
// count when on the tangent plane (within 2% of the view distance), of similar normal and of
// similar roughness. Output: the filtered demodulated radiance (rgb) and the weight the
// composite gives it against the SH specular (a, shared/rt_specular.h's seam).
#extension GL_GOOGLE_include_directive : require
#include "shared/brdf_lut.h"
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/rt.h"
#include "shared/rt_specular.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kRtBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kRtBindingNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtBindingSpecularAccumulated) uniform sampler2D accumulated;
layout(set = 0, binding = kRtBindingSpecularHit) uniform sampler2D hitDistances;
layout(set = 0, binding = kRtBindingSpecularFiltered, rgba16f) uniform writeonly image2D outFiltered;
layout(push_constant) uniform SpecularPush { RtSpecularPush sp; };

#include "common/poisson_disk.glsl"
#include "common/camera.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 centre = texelFetch(accumulated, p, 0);
  float depth = texelFetch(gDepth, p, 0).r;
  vec2 thresholds = tlRtSpecularRoughness(sp.specularRoughness);
  float roughness = clamp(texelFetch(gMaterial, p, 0).x, kBrdfMinRoughness, 1.0);
  float weight = tlRtSpecularTracedWeight(roughness, thresholds.x);
  if (depth <= 0.0 || centre.a <= 0.0 || weight <= 0.0) {
    imageStore(outFiltered, p, vec4(0.0));
    return;
  }
  if (tlRtSpecularIsMirror(texelFetch(gMaterial, p, 0).x, thresholds.y)) {
    imageStore(outFiltered, p, vec4(centre.rgb, weight));
    return;
  }
  vec3 position = pixelPosition(p, depth);
  vec3 n = tlOctDecode(texelFetch(gNormal, p, 0).xy);
  float w = viewW(position);
  float alpha = roughness * roughness;
  float footprint = texelFetch(hitDistances, p, 0).r * alpha / max(pixelFootprint(w), 1e-30);
  float radius = min(footprint / sqrt(max(centre.a, 1.0)), sp.maxRadius);
  if (radius < 0.5) {
    imageStore(outFiltered, p, vec4(centre.rgb, weight));
    return;
  }
  float c = cos(sp.rotation), s = sin(sp.rotation);
  mat2 rotate = mat2(c, s, -s, c);
  vec3 sum = centre.rgb;
  float total = 1.0;
  for (int i = 0; i < 16; ++i) {
    ivec2 q = p + ivec2(round(rotate * kPoissonDisk16[i] * radius));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) || q == p) continue;
    float dq = texelFetch(gDepth, q, 0).r;
    vec4 tap = texelFetch(accumulated, q, 0);
    if (dq <= 0.0 || tap.a <= 0.0) continue;
    vec3 pq = pixelPosition(q, dq);
    if (abs(dot(pq - position, n)) > 0.02 * w) continue;  // off the tangent plane
    vec3 nq = tlOctDecode(texelFetch(gNormal, q, 0).xy);
    float rq = clamp(texelFetch(gMaterial, q, 0).x, kBrdfMinRoughness, 1.0);
    // Normals: the lobe's width sets how much a turn of the normal moves the reflection.
    float normalWeight = pow(max(dot(n, nq), 0.0), 2.0 / max(alpha, 1e-3));
    float roughnessWeight = max(1.0 - abs(rq - roughness) / max(0.25 * roughness, 1e-3), 0.0);
    float tapWeight = normalWeight * roughnessWeight;
    sum += tap.rgb * tapWeight;
    total += tapWeight;
  }
  imageStore(outFiltered, p, vec4(sum / total, weight));
}
