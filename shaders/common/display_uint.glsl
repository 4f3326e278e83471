// The integer display, for 2D sources and (DISPLAY_3D) a slice of a 3D source: ids as stable
// colours, and for 2D hit records their distance or normal.
#include "shared/display.h"
#include "shared/packing.h"
#include "shared/rt.h"

layout(local_size_x = 8, local_size_y = 8) in;
#ifdef DISPLAY_3D
layout(set = 0, binding = kDisplaySource) uniform usampler3D source;
#else
layout(set = 0, binding = kDisplaySource) uniform usampler2D source;
#endif
layout(set = 0, binding = kDisplayInstanceId) uniform usampler2D instanceId;
layout(set = 0, binding = kDisplayOutput, rgba8) uniform writeonly image2D display;
layout(push_constant) uniform Push { DisplayPush push; };

#include "common/display_outline.glsl"

// A stable, well-spread colour per integer value; 0 stays black.
vec3 idColor(uint v) {
  if (v == 0u) return vec3(0.0);
  uint h = v * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(display);
  if (any(greaterThanEqual(p, size))) return;
  vec2 uv = sourceUv(p, size);
#ifdef DISPLAY_3D
  ivec3 volumeSize = textureSize(source, 0);
  ivec2 sourceSize = volumeSize.xy;
#else
  ivec2 sourceSize = textureSize(source, 0);
#endif
  vec3 c = vec3(0.04);
  if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
#ifdef DISPLAY_3D
    // A slice of a volume: its integers as colours (a volume's meanings are the stored values).
    uvec4 v = texelFetch(source, ivec3(ivec2(uv * vec2(sourceSize)), min(int(push.slice * float(volumeSize.z)), volumeSize.z - 1)), 0);
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
