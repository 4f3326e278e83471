// The integer display, for 2D sources and (DISPLAY_3D) a slice of a 3D source: ids as stable
// colours, and for 2D hit records their distance or normal.
#include "shared/display.h"
#include "shared/packing.h"
#include "shared/rt.h"

#define DISPLAY_INTEGER 1
#include "common/display_bindings.glsl"

// A stable, well-spread colour per integer value; 0 stays black.
vec3 idColor(uint v) {
  if (v == 0u) return vec3(0.0);
  uint h = v * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
  ivec2 p, size;
  vec2 uv;
  if (!displayPixel(p, size, uv)) return;
  ivec2 sourceSize = displaySourceSize();
  vec3 c = vec3(0.04);
  if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
#ifdef DISPLAY_3D
    // A slice of a volume: its integers as colours (a volume's meanings are the stored values).
    int depth = textureSize(source, 0).z;
    uvec4 v = texelFetch(source, ivec3(ivec2(uv * vec2(sourceSize)), min(int(push.slice * float(depth)), depth - 1)), 0);
#else
    uvec4 v = texelFetch(source, ivec2(uv * vec2(sourceSize)), 0);
#endif
    if (push.meaning == kDisplayMeaningHitDistance) {
      // Near blue to far red over the range; a miss and a pending ray flat (the legend says which).
      c = tlRtIsMiss(v.r)      ? tlDisplayMissColour()
          : tlRtIsPending(v.r) ? tlDisplayPendingColour()
                               : tlDisplayFalseColour((tlRtHitDistance(v.r) - push.rangeMin) /
                                                      max(push.rangeMax - push.rangeMin, 1e-20));
    } else if (push.meaning == kDisplayMeaningHitNormal) {
      c = tlOctDecodeSnorm16(v.r) * 0.5 + 0.5;
    } else {
      c = idColor(v.r);
    }
  }
  c = grid(uv, size, sourceSize, c);
  imageStore(display, p, vec4(outline(uv, c), 1.0));
}
