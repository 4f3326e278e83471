// What every display shader binds: its source (2D, or 3D under DISPLAY_3D; integer under
// DISPLAY_INTEGER), the G-buffer's instance ids (the selection's outline), the viewport image
// and the push constants; then the outline and the source UV (common/display_outline.glsl), and
// where each invocation's viewport pixel lies in the source.
layout(local_size_x = 8, local_size_y = 8) in;
#if defined(DISPLAY_3D) && defined(DISPLAY_INTEGER)
layout(set = 0, binding = kDisplaySource) uniform usampler3D source;
#elif defined(DISPLAY_3D)
layout(set = 0, binding = kDisplaySource) uniform sampler3D source;
#elif defined(DISPLAY_INTEGER)
layout(set = 0, binding = kDisplaySource) uniform usampler2D source;
#else
layout(set = 0, binding = kDisplaySource) uniform sampler2D source;
#endif
layout(set = 0, binding = kDisplayInstanceId) uniform usampler2D instanceId;
layout(set = 0, binding = kDisplayOutput, rgba8) uniform writeonly image2D display;
layout(push_constant) uniform Push { DisplayPush push; };

#include "common/display_outline.glsl"

// The source's size in texels (a volume's slice), and this invocation's viewport pixel, the
// viewport's size and the source UV it shows; false past the viewport's edge.
ivec2 displaySourceSize() {
#ifdef DISPLAY_3D
  return textureSize(source, 0).xy;
#else
  return textureSize(source, 0);
#endif
}
bool displayPixel(out ivec2 p, out ivec2 size, out vec2 uv) {
  p = ivec2(gl_GlobalInvocationID.xy);
  size = imageSize(display);
  uv = sourceUv(p, size);
  return all(lessThan(p, size));
}
