// Shared by the legacy path's compute passes: frame, push constants, G-buffer depth and
// normal, and camera-relative positions.
#include "shared/frame.h"
#include "shared/legacy.h"
#include "shared/packing.h"

layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingDepth) uniform sampler2D gDepth;
layout(set = 0, binding = kLegacyBindingNormal) uniform sampler2D gNormal;
layout(push_constant) uniform Push { LegacyPush push; };

#include "common/camera.glsl"

vec3 pixelNormal(ivec2 p) { return tlOctDecode(texelFetch(gNormal, p, 0).xy); }
// A reduced-resolution image (1/divisor per axis): its size, and the full-resolution pixel
// each of its texels stands for.
ivec2 reducedSize(uint divisor) { return (ivec2(frame.viewport.xy) + int(divisor) - 1) / int(divisor); }
ivec2 fullPixel(ivec2 q, uint divisor) { return min(q * int(divisor), ivec2(frame.viewport.xy) - 1); }
