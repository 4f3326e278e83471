// Sun visibility through the shadow map, shared by the composite and the voxelizer. The
// includer declares `frame` (FrameConstants) and `sunShadow` (sampler2DShadow); with
// TL_SUN_SHADOW_PCSS defined also `sunShadowDepth` (sampler2D, the same map) for
// percentage-closer soft shadows.
// 3x3 PCF of hardware 2x2 comparisons. Receivers are pushed along the normal by a few
// texels and towards the sun by the depth bias, both in world units, which keeps acne
// away at any distance from the origin.
float sunVisibility(vec3 position, vec3 normal) {
  if ((frame.flags & kFrameFlagSunShadows) == 0u) return 1.0;
  vec3 l = frame.sunToLight.xyz;
  float texel = frame.shadowParams.x;
  float slope = sqrt(max(1.0 - dot(normal, l) * dot(normal, l), 0.0));
  vec3 offset = normal * (frame.shadowParams.z * texel * max(slope, 0.2)) + l * frame.shadowParams.y;
  vec4 clip = frame.sunViewProj * vec4(position + offset, 1.0);
  vec3 s = clip.xyz / clip.w;
  vec2 uv = s.xy * 0.5 + 0.5;
  if (s.z >= 1.0) return 1.0;
  float size = frame.shadowParams.w;
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(sunShadow, vec3(uv + vec2(x, y) / size, s.z));
  return sum / 9.0;
}


#ifdef TL_SUN_SHADOW_PCSS
// Percentage-closer soft shadows (Fernando 2005) for a sun of angular radius theta: the
// blockers' mean depth over the region that could hide the sun from the receiver gives the
// penumbra half-width tan(theta) * (receiver - blocker) in metres, and PCF over that radius.
// Sixteen Poisson taps per step, rotated per pixel.
#include "common/poisson_disk.glsl"

// What the PCSS estimate found: the visibility, and the receiver's distance to the blockers'
// mean depth along the sun in metres (-1: no blocker in the search region; 0: the penumbra is
// below a texel, so the plain PCF answered). HRTS blends by that distance.
struct SunShadowEstimate {
  float visibility;
  float blockerDistance;
};

SunShadowEstimate sunShadowSoft(vec3 position, vec3 normal, ivec2 pixel) {
  if ((frame.flags & kFrameFlagSunShadows) == 0u) return SunShadowEstimate(1.0, -1.0);
  float texel = frame.shadowParams.x, size = frame.shadowParams.w;
  float tanSun = tan(frame.sunToLight.w);
  float metres = frame.shadowSoftness.x;
  float maxRadius = frame.shadowSoftness.y;
  if (frame.shadowSoftness.z == 0.0) return SunShadowEstimate(sunVisibility(position, normal), 0.0);
  vec3 l = frame.sunToLight.xyz;
  float slope = sqrt(max(1.0 - dot(normal, l) * dot(normal, l), 0.0));
  vec3 offset = normal * (frame.shadowParams.z * texel * max(slope, 0.2)) + l * frame.shadowParams.y;
  vec4 clip = frame.sunViewProj * vec4(position + offset, 1.0);
  vec3 s = clip.xyz / clip.w;
  if (s.z >= 1.0) return SunShadowEstimate(1.0, -1.0);
  vec2 uv = s.xy * 0.5 + 0.5;
  // Any blocker that can hide part of the sun lies within tan(theta) * (its height) of the
  // receiver: search that far (at most the largest filter).
  float searchTexels = clamp(tanSun * s.z * metres / texel, 1.0, maxRadius);
  // Penumbra below a texel: plain PCF.
  if (searchTexels <= 1.5) return SunShadowEstimate(sunVisibility(position, normal), 0.0);
  float angle = 6.2831853 * fract(52.9829189 * fract(dot(vec2(pixel), vec2(0.06711056, 0.00583715))));
  mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
  float blockerSum = 0.0, blockers = 0.0;
  for (int i = 0; i < 16; ++i) {
    float d = textureLod(sunShadowDepth, uv + rotation * kPoissonDisk16[i] * (searchTexels / size), 0.0).r;
    if (d < s.z) blockerSum += d, blockers += 1.0;
  }
  if (blockers == 0.0) return SunShadowEstimate(1.0, -1.0);
  float blockerDistance = (s.z - blockerSum / blockers) * metres;
  float penumbraTexels = clamp(tanSun * blockerDistance / texel, 1.0, maxRadius);
  float sum = 0.0;
  for (int i = 0; i < 16; ++i) sum += texture(sunShadow, vec3(uv + rotation * kPoissonDisk16[i] * (penumbraTexels / size), s.z));
  return SunShadowEstimate(sum / 16.0, blockerDistance);
}

float sunVisibilitySoft(vec3 position, vec3 normal, ivec2 pixel) { return sunShadowSoft(position, normal, pixel).visibility; }

#ifdef TL_SUN_VISIBILITY_HYBRID
// The shading passes' sun visibility (the composite, ibuffer.light): shadow.sun.hybrid's buffer
// where the path traced it (CompositePush kCompositeHasSunVisibility; the includer declares
// `push` and `sunVisibilityHybrid`), else PCSS.
float sunVisibilityShading(vec3 position, vec3 normal, ivec2 pixel) {
  return (push.flags & kCompositeHasSunVisibility) != 0u ? texelFetch(sunVisibilityHybrid, pixel, 0).r
                                                          : sunVisibilitySoft(position, normal, pixel);
}
#endif
#endif
