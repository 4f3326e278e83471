#version 460
// One pass of the RT path's spatial denoiser on the SH irradiance (Metro Exodus, "little
// monster"): 3x3 variance of the input; radius = base * F(viewZ) * F(variance) * F(AO) (the
// world radius projected at this depth, shrunk where the signal is already clean and in dark
// corners); an adaptive step through a 16-tap Poisson disk (small radius, fewer taps) rotated
// per frame, not per pixel; a step-function weight on the distance to the centre's tangent
// plane (absolute, so rounded objects are not skipped); pass 2 adds a linear normal weight.
// Beyond Metro: an edge-stopping weight on luma against the accumulation's own noise (its
// temporal second moment), so light is not carried across a real change of irradiance on one
// plane, such as a doorway's threshold, which the plane and normal weights cannot see; and
// taps of other normals are normalised by the share of this pixel's irradiance their
// hemisphere holds (tapCoverage), so light they never sampled is not lost. The output keeps
// part of the input: lerp(denoised, input, 0.5 * accumulation speed). And the radius shrinks
// with the harmonic mean of the GI rays' hit distances (accumulated by rt.temporal, as ReBLUR
// scales its radius by hit distance): irradiance changes across a surface on the scale of the
// distance to what it sees, so under an overhang or a table a radius of the room's scale
// carries in the brighter light from beyond the overhang's edge.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/packing.h"
#include "shared/rt.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kRtBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kRtBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kRtBindingNormal) uniform sampler2D gNormal;
layout(set = 0, binding = kRtDenoiseInShY) uniform sampler2D inShY;
layout(set = 0, binding = kRtDenoiseInCoCgAo) uniform sampler2D inCoCgAo;
layout(set = 0, binding = kRtDenoiseLumaMoment) uniform sampler2D lumaMoment;
layout(set = 0, binding = kRtBindingBaseColor) uniform sampler2D gBaseColor;
layout(set = 0, binding = kRtBindingMaterial) uniform sampler2D gMaterial;
layout(set = 0, binding = kRtDenoiseOutShY, rgba16f) uniform writeonly image2D outShY;
layout(set = 0, binding = kRtDenoiseOutCoCgAo, rgba16f) uniform writeonly image2D outCoCgAo;
layout(push_constant) uniform Push { RtDenoisePush push; };

#include "common/poisson_disk.glsl"

#include "common/camera.glsl"

// A tap's weight falls as exp(-|luma difference| / (kLumaSigmas * its standard error)): a
// difference of a few standard errors of the two accumulated means is noise, one of many is
// a real change of light. (SVGF's luminance weight, with the variance of the means.)
const float kLumaSigmas = 4.0;

// The radius is at most this many times the harmonic mean hit distance: a blur of radius r over
// light that changes on the scale d errs by about (r/d)^2 of the change (measured under a roof
// 1 m up: 1.0x leaves 20% of the excess, 0.25x 6%; cornell, atrium and doorway_room improve
// with it, slit_corridor loses 1.6%).
const float kHitRadiusScale = 0.25;

// The squared standard error of a pixel's accumulated luma: its samples' variance (the temporal
// pass's second moment less the squared mean) over the frames accumulated. With fewer than
// four frames the second moment says little: the 3x3 spread of the input stands in for it.
// (Past the accumulation window the running mean weighs samples unequally and its variance is
// smaller than this: the estimate errs towards blurring. In pass 2 `mean` is pass 1's output.)
float lumaStandardError2(float mean, float meanSquare, float frames, float spatialVariance) {
  float n = max(frames, 1.0);
  float variance = n >= 4.0 ? max(meanSquare - mean * mean, 0.0) : spatialVariance;
  return variance / n;
}

// What a tap's SH, resolved at this pixel's normal, holds of the irradiance here, relative
// (the divisor of its weight). It was gathered over the tap's own hemisphere: the directions
// above this pixel's horizon but below the tap's it never saw. Where the surface is convex
// (this pixel lies behind the tap's tangent plane) they look out into the same surroundings
// as the rest, so they count with the radiance of those it did see: for a uniform sky the
// resolved share is tlShHemisphereCoverage, exact in the white furnace. Where it is concave
// (a floor at the foot of a wall: this pixel in front of the tap's surface) they look at the
// tap's own surface, whose radiance is its albedo times the light it receives (the assumption
// of shared/shading.h tlMultiBounceAo): the missing share (1 - c) counts with rho, so the
// tap's SH holds c / (c + (1 - c) rho) of this pixel's irradiance. A white surface (rho = 1)
// gives c again: the furnace stays exact in a closed room too.
float tapCoverage(ivec2 q, vec3 nq, vec3 offset, float cosNormals) {
  float c = tlShHemisphereCoverage(cosNormals, kShOpenSkyDirectionality);
  if (dot(nq, offset) >= 0.0) return c;  // convex (or flat): this pixel behind the tap's plane
  vec3 albedo = tlMaterialHitAlbedo(texelFetch(gBaseColor, q, 0).rgb, texelFetch(gMaterial, q, 0).g,
                                    tlFrameMaterials(frame.flags));
  float rho = clamp(tlLuminance(albedo), 0.0, 1.0);
  return c / (c + (1.0 - c) * rho);
}

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
  float spatialVariance = sigma * sigma;
  vec2 moments0 = texelFetch(lumaMoment, p, 0).rg;  // mean squared luma, mean inverse hit distance
  float error0 = lumaStandardError2(shY0.x, moments0.x, coCgAo0.w, spatialVariance);
  float fAo = mix(0.5, 1.0, clamp(coCgAo0.z, 0.0, 1.0));
  float fHit = moments0.y > 0.0 ? clamp(kHitRadiusScale / (moments0.y * push.hitDistanceCap), 0.0, 1.0) : 1.0;
  float radius = clamp(push.baseRadius * fVariance * fAo * fHit / pixelFootprint(w0), 1.0, 48.0);
  int step = radius < 4.0 ? 4 : (radius < 8.0 ? 2 : 1);

  float c = cos(push.rotation), s = sin(push.rotation);
  mat2 rotation = mat2(c, s, -s, c);
  vec4 shY = shY0;
  vec2 coCg = coCgAo0.xy;
  float coverage = 1.0;
  float plane = push.planeDistance * w0;
  for (int i = 0; i < 16; i += step) {
    ivec2 q = p + ivec2(round(rotation * kPoissonDisk16[i] * radius));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) || q == p) continue;
    float d = texelFetch(gDepth, q, 0).r;
    if (d <= 0.0) continue;
    vec3 Pq = pixelPosition(q, d);
    if (abs(dot(n0, Pq - P0)) > plane) continue;  // off the tangent plane: weight 0
    vec3 nq = tlOctDecode(texelFetch(gNormal, q, 0).xy);
    float cosNormals = dot(n0, nq);
    float k = push.normalWeight != 0u ? max(cosNormals, 0.0) : 1.0;
    if (k <= 0.0) continue;
    vec4 shYq = texelFetch(inShY, q, 0);
    vec4 coCgAoq = texelFetch(inCoCgAo, q, 0);
    // Edge-stopping on luma: a difference the two estimates' noise cannot explain is a real
    // change of light (a doorway's threshold, a contact shadow), which blurring would carry
    // across. The floor of 1% of the pair's mean luma keeps converged pixels together.
    float errorQ = lumaStandardError2(shYq.x, texelFetch(lumaMoment, q, 0).r, coCgAoq.w, spatialVariance);
    float scale = max(sqrt(error0 + errorQ), 0.005 * (abs(shY0.x) + abs(shYq.x))) + 1e-8;
    k *= exp(-abs(shYq.x - shY0.x) / (kLumaSigmas * scale));
    shY += k * shYq;
    coCg += k * coCgAoq.xy;
    coverage += k * tapCoverage(q, nq, Pq - P0, cosNormals);
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
