// The environment map: an equirectangular image of the radiance arriving from every direction
// (a latitude-longitude HDRI), rotated about +Y and scaled by an intensity. The uniform sky
// (FrameConstants::skyRadiance) stays the simplest environment; with a map, kFrameFlagEnvironment
// is set and every path reads it instead:
//   - the reference path: the texels themselves from the environment table (set 0 binding
//     kBindingEnvironment), importance-sampled by luminance x sin(theta) and combined with the
//     BRDF's own samples by multiple importance sampling (common/environment.glsl);
//   - direct, legacy and rt: its projection on spherical harmonics up to order 2
//     (FrameConstants::envSh, nine RGB coefficients of the radiance, rotation and intensity
//     applied): irradiance by Ramamoorthi and Hanrahan's convolution, radiance along a
//     direction (rt's misses, legacy's cones, the specular sky) as the band-limited sum.
// A scene without a map has neither the table nor a pass, and the flag is off.
//
// Directions. Texel (c, r) of a W x H map covers u in [c, c+1)/W and v in [r, r+1)/H; the map's
// frame has theta = pi v from +Y (row 0 is the zenith) and phi = 2 pi u, with the image's centre
// (u = 0.5) straight ahead along -Z (glTF's forward) and u growing towards +X, as a panorama
// looks from inside. The world direction is the map's turned by the rotation about +Y
// (counter-clockwise seen from above).
#ifndef TL_SHARED_ENVIRONMENT_H
#define TL_SHARED_ENVIRONMENT_H
#include "common.h"

TL_BEGIN
// Set-0 binding of the environment table in the reference path's passes.
TL_CONST uint kBindingEnvironment = 50u;
// FrameConstants::flags bit: an environment map replaces the uniform sky.
TL_CONST uint kFrameFlagEnvironment = 8u;

// The environment table, one std430 float array: W*H texels as vec4 (rgb radiance as stored,
// before the intensity; a unused), then the marginal CDF over rows (H + 1 values, 0 .. 1),
// then each row's conditional CDF over its columns (W + 1 values each, 0 .. 1). A texel's
// weight is its luminance times sin(theta) at its centre.
TL_FN uint tlEnvMarginalOffset(uint w, uint h) { return 4u * w * h; }
TL_FN uint tlEnvConditionalOffset(uint w, uint h, uint row) { return 4u * w * h + (h + 1u) + row * (w + 1u); }
TL_FN uint tlEnvTableFloats(uint w, uint h) { return 4u * w * h + (h + 1u) + h * (w + 1u); }

// Map direction of (u, v).
TL_FN vec3 tlEquirectDirection(vec2 uv) {
  float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
  float s = sin(theta);
  return vec3(-s * sin(phi), cos(theta), s * cos(phi));
}
// (u, v) of a map direction (unit length).
TL_FN vec2 tlEquirectUv(vec3 d) {
  float u = atan(-d.x, d.z) * (0.5f * kInvPi);
  if (u < 0.0f) u += 1.0f;
  return vec2(min(u, 0.99999994f), min(acos(clamp(d.y, -1.0f, 1.0f)) * kInvPi, 0.99999994f));
}
// World <-> map frame: rotation about +Y by the angle whose cosine and sine are cs.
TL_FN vec3 tlEnvMapToWorld(vec3 d, vec2 cs) { return vec3(cs.x * d.x + cs.y * d.z, d.y, -cs.y * d.x + cs.x * d.z); }
TL_FN vec3 tlEnvWorldToMap(vec3 d, vec2 cs) { return vec3(cs.x * d.x - cs.y * d.z, d.y, cs.y * d.x + cs.x * d.z); }

// The nine real spherical harmonics up to order 2 at a unit direction (x, y, z).
TL_FN float tlSh9Basis(uint i, vec3 d) {
  if (i == 0u) return 0.282094792f;
  if (i == 1u) return 0.488602512f * d.y;
  if (i == 2u) return 0.488602512f * d.z;
  if (i == 3u) return 0.488602512f * d.x;
  if (i == 4u) return 1.092548431f * d.x * d.y;
  if (i == 5u) return 1.092548431f * d.y * d.z;
  if (i == 6u) return 0.315391565f * (3.0f * d.z * d.z - 1.0f);
  if (i == 7u) return 1.092548431f * d.x * d.z;
  return 0.546274215f * (d.x * d.x - d.y * d.y);
}
// The clamped cosine's convolution weights per band (Ramamoorthi & Hanrahan 2001): pi, 2pi/3, pi/4.
TL_FN float tlSh9CosineBand(uint i) { return i == 0u ? kPi : (i < 4u ? 2.0f * kPi / 3.0f : 0.25f * kPi); }
// From the nine coefficients (rgb) of a radiance: the irradiance on a surface of unit normal n,
// and the band-limited radiance along unit direction d, both clamped at 0 (ringing).
TL_FN vec3 tlEnvShIrradiance(vec4 sh[9], vec3 n) {
  vec3 e = vec3(0.0f);
  for (uint i = 0u; i < 9u; ++i) e += vec3(sh[i]) * (tlSh9CosineBand(i) * tlSh9Basis(i, n));
  return max(e, vec3(0.0f));
}
TL_FN vec3 tlEnvShRadiance(vec4 sh[9], vec3 d) {
  vec3 l = vec3(0.0f);
  for (uint i = 0u; i < 9u; ++i) l += vec3(sh[i]) * tlSh9Basis(i, d);
  return max(l, vec3(0.0f));
}
TL_END

#endif
