// Shared by the legacy path's compute passes: frame, push constants, G-buffer depth and
// normal, and camera-relative positions.
#include "shared/frame.h"
#include "shared/legacy.h"
#include "shared/packing.h"

layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLegacyBindingNormal) uniform sampler2D gNormal;
layout(push_constant) uniform Push { LegacyPush push; };

vec3 cameraRelativePosition(vec2 uv, float depth) {
  vec4 p = frame.invViewProj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}
vec3 pixelPosition(ivec2 p, float depth) { return cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth); }
vec3 pixelNormal(ivec2 p) { return tlOctDecode(texelFetch(gNormal, p, 0).xy); }
float viewW(vec3 position) { return (frame.viewProj * vec4(position, 1.0)).w; }
// View distance along the axis straight from a reversed-Z infinite depth: depth = near / w.
float depthToViewW(float depth) { return frame.proj[3][2] / depth; }
// A reduced-resolution image (1/divisor per axis): its size, and the full-resolution pixel
// each of its texels stands for.
ivec2 reducedSize(uint divisor) { return (ivec2(frame.viewport.xy) + int(divisor) - 1) / int(divisor); }
ivec2 fullPixel(ivec2 q, uint divisor) { return min(q * int(divisor), ivec2(frame.viewport.xy) - 1); }
