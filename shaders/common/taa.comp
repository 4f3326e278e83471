#version 460
// Temporal anti-aliasing (shared/taa.h): this frame's jittered composite blended into the
// reprojected history, the history first clipped to the box of the current 3x3 neighbourhood
// in YCoCg so what changed (disocclusion, moving light, a switched-off lamp) does not ghost.
// Linear radiance in, linear radiance out, blended without a luminance weight: a weight of
// 1 / (1 + luma) (Karis 2014) steadies fireflies but pulls every edge against a bright
// emitter towards its dark side (on cornell it made the image further from supersampling
// than no TAA at all); the RT path suppresses its fireflies before this.
#extension GL_GOOGLE_include_directive : require
#include "shared/color.h"
#include "shared/frame.h"
#include "shared/taa.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kTaaBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kTaaBindingCurrent) uniform sampler2D current;
layout(set = 0, binding = kTaaBindingHistory) uniform sampler2D history;
layout(set = 0, binding = kTaaBindingMotion) uniform sampler2D motion;
layout(set = 0, binding = kTaaBindingOutput, rgba32f) uniform writeonly image2D outResolved;  // kCompositeHdrFormat
layout(push_constant) uniform Push { TaaPush push; };

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec3 c = texelFetch(current, p, 0).rgb;
  if (!finite3(c)) c = vec3(0.0);
  // The neighbourhood's box in YCoCg.
  vec3 lo = vec3(1e30), hi = vec3(-1e30);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec3 s = texelFetch(current, clamp(p + ivec2(x, y), ivec2(0), size - 1), 0).rgb;
      if (!finite3(s)) continue;
      vec3 ycocg = tlRgbToYCoCg(s);
      lo = min(lo, ycocg);
      hi = max(hi, ycocg);
    }
  vec3 resolved = c;
  vec2 uv = (vec2(p) + 0.5) * frame.viewport.zw;
  vec2 previousUv = uv - texelFetch(motion, p, 0).xy;
  bool onScreen = all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThanEqual(previousUv, vec2(1.0)));
  if (push.historyValid != 0u && onScreen && hi.x >= lo.x) {
    vec3 h = textureLod(history, previousUv, 0.0).rgb;
    if (finite3(h)) {
      h = tlYCoCgToRgb(tlTaaClipToBox(tlRgbToYCoCg(h), lo, hi));
      resolved = mix(h, c, push.blend);
    }
  }
  imageStore(outResolved, p, vec4(max(resolved, vec3(0.0)), 1.0));
}
