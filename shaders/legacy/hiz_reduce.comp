#version 460
// Mip m + 1 of the hierarchical depth from mip m (shared/legacy_reflections.h): the nearest
// (largest reversed-Z) depth of the 2x2 texels below. Mip sizes round down, so where mip m has
// an odd side the last texel of mip m + 1 covers the three texels left there: the last texel
// of every mip bounds the rest of the image, and the march reads it for the cells past it.
#extension GL_GOOGLE_include_directive : require
#include "shared/legacy_reflections.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingHizSource, r32f) uniform readonly image2D below;
layout(set = 0, binding = kLegacyBindingHizOut, r32f) uniform writeonly image2D hizOut;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(hizOut)))) return;
  ivec2 size = imageSize(below);
  float nearest = 0.0;
  ivec2 last = imageSize(hizOut) - 1;
  ivec2 span = ivec2(q.x == last.x && (size.x & 1) != 0 ? 3 : 2, q.y == last.y && (size.y & 1) != 0 ? 3 : 2);
  for (int y = 0; y < span.y; ++y)
    for (int x = 0; x < span.x; ++x) {
      ivec2 p = 2 * q + ivec2(x, y);
      if (all(lessThan(p, size))) nearest = max(nearest, imageLoad(below, p).r);
    }
  imageStore(hizOut, q, vec4(nearest));
}
