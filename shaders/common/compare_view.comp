#version 460
// Compare view: the left and right images tonemapped like the final image, split by a wipe
// line, or the per-pixel difference of their display values in false colour.
#extension GL_GOOGLE_include_directive : require
#include "shared/color.h"
#include "shared/compare_view.h"
#include "shared/display.h"
#include "shared/frame.h"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kCompareViewFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kCompareViewLeft) uniform sampler2D leftImage;
layout(set = 0, binding = kCompareViewRight) uniform sampler2D rightImage;
layout(set = 0, binding = kCompareViewOutput, rgba8) uniform writeonly image2D outDisplay;
layout(push_constant) uniform Push { CompareViewPush push; };

// Display-linear value (before sRGB encoding) of a side, or dark grey while it has no image.
vec3 displayOf(sampler2D image, ivec2 p, bool valid) {
  if (!valid) return vec3(0.02);
  return tlTonemapAces(max(texelFetch(image, p, 0).rgb, vec3(0.0)) * frame.exposure);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(outDisplay);
  if (any(greaterThanEqual(p, size))) return;
  bool leftValid = (push.flags & kCompareViewLeftValid) != 0u, rightValid = (push.flags & kCompareViewRightValid) != 0u;
  vec3 colour;
  if (push.mode == kCompareViewDifference) {
    // Difference of what the eye sees (sRGB-encoded), the largest channel: 1/scale is the top.
    vec3 a = tlLinearToSrgb(displayOf(leftImage, p, leftValid)), b = tlLinearToSrgb(displayOf(rightImage, p, rightValid));
    vec3 d = abs(a - b);
    colour = tlSrgbToLinear(tlDisplayFalseColour(max(d.r, max(d.g, d.b)) * push.differenceScale));
  } else {
    int split = int(push.wipe * float(size.x) + 0.5);
    colour = p.x < split ? displayOf(leftImage, p, leftValid) : displayOf(rightImage, p, rightValid);
    if (p.x == split || p.x == split - 1) colour = vec3(1.0);  // the wipe line
  }
  imageStore(outDisplay, p, vec4(tlLinearToSrgb(colour), 1.0));
}
