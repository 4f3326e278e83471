// The float display, for 2D sources and (DISPLAY_3D) a slice of a 3D source.
#include "shared/display.h"
#include "shared/color.h"
#include "shared/packing.h"
#include "shared/sh.h"

#include "common/display_bindings.glsl"
#ifndef DISPLAY_3D
layout(set = 0, binding = kDisplayCompanionA) uniform sampler2D companionA;
layout(set = 0, binding = kDisplayCompanionB) uniform sampler2D companionB;
#endif

void main() {
  ivec2 p, size;
  vec2 uv;
  if (!displayPixel(p, size, uv)) return;
  ivec2 sourceSize = displaySourceSize();
#ifdef DISPLAY_3D
  vec4 v = textureLod(source, vec3(uv, push.slice), 0.0);
#else
  vec4 v = textureLod(source, uv, 0.0);
#endif
  vec3 c;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) {
    c = vec3(0.04);  // outside the image (zoomed out or panned)
  } else if (push.mode == kDisplayModeFinal) {
    c = v.rgb;
#ifndef DISPLAY_3D
  } else if (push.meaning != kDisplayMeaningNone &&
             texelFetch(instanceId, ivec2(uv * vec2(textureSize(instanceId, 0))), 0).r == 0u) {
    c = vec3(0.04);  // no surface: a normal or the irradiance at it means nothing here
  } else if (push.meaning == kDisplayMeaningOctNormal) {
    c = tlOctDecode(v.rg) * 0.5 + 0.5;  // a direction as colour: +X red, +Y green, +Z blue
  } else if (push.meaning == kDisplayMeaningAo) {
    // The visibility as the grey level itself (not sRGB-encoded): what AO views show, so 0.5
    // reads as mid grey. NaN magenta, negative blue, above 1 yellow (more than a half-float step:
    // rounding) — none is a visibility.
    c = vec3(clamp(v.r, 0.0, 1.0));
    if ((push.flags & kDisplayFlagHighlight) != 0u) {
      if (isnan(v.r)) c = vec3(1.0, 0.0, 1.0);
      else if (v.r < 0.0) c = vec3(0.0, 0.4, 1.0);
      else if (v.r > 1.001) c = vec3(1.0, 1.0, 0.0);
    }
  } else if (push.meaning == kDisplayMeaningShIrradiance) {
    // What the SH means at this pixel: the irradiance it resolves to at the G-buffer normal
    // (companions sampled at the same relative position: the cones may be quarter size).
    ShLumaCoCg sh = tlShMake(v, textureLod(companionA, uv, 0.0).rg);
    vec3 e = tlShResolveIrradiance(sh, tlOctDecode(textureLod(companionB, uv, 0.0).rg));
    vec3 t = (e - push.rangeMin) / max(push.rangeMax - push.rangeMin, 1e-20);
    c = tlLinearToSrgb(clamp(t, 0.0, 1.0));
    // Negative irradiance is wrong (SH ringing); raw negative coefficients are not.
    if ((push.flags & kDisplayFlagHighlight) != 0u) {
      if (any(isnan(e))) c = vec3(1.0, 0.0, 1.0);
      else if (any(isinf(e))) c = vec3(1.0, 1.0, 0.0);
      else if (any(lessThan(e, vec3(0.0)))) c = vec3(0.0, 0.4, 1.0);
    }
#endif
  } else {
    if (push.channels == 1u) v = vec4(v.r, v.r, v.r, 1.0);
    if (push.channels == 2u) v = vec4(v.r, v.g, 0.0, 1.0);
    if (push.channels == 3u) v.a = 1.0;
    vec3 shown = push.channel == kDisplayChannelR   ? vec3(v.r)
                 : push.channel == kDisplayChannelG ? vec3(v.g)
                 : push.channel == kDisplayChannelB ? vec3(v.b)
                 : push.channel == kDisplayChannelA ? vec3(v.a)
                 : push.channel == kDisplayChannelLuminance ? vec3(tlLuminance(v.rgb))
                                                            : v.rgb;
    vec3 t = (shown - push.rangeMin) / max(push.rangeMax - push.rangeMin, 1e-20);
    c = (push.flags & kDisplayFlagFalseColour) != 0u ? tlDisplayFalseColour(t.r) : tlLinearToSrgb(clamp(t, 0.0, 1.0));
    if ((push.flags & kDisplayFlagHighlight) != 0u) {
      bvec3 nan = isnan(shown), inf = isinf(shown);
      if (any(nan)) c = vec3(1.0, 0.0, 1.0);
      else if (any(inf)) c = vec3(1.0, 1.0, 0.0);
      else if ((push.flags & kDisplayFlagNegativesValid) == 0u && any(lessThan(shown, vec3(0.0)))) c = vec3(0.0, 0.4, 1.0);
    }
  }
  c = grid(uv, size, sourceSize, c);
  imageStore(display, p, vec4(outline(uv, c), 1.0));
}
