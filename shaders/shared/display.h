// The editor's display pass (engine/lighting/common/display_pass.cpp): shows the final
// image or any other resource of the frame — one channel or all, over a chosen range, in
// false colour, with invalid values highlighted, zoomed with a texel grid, a slice of a 3D
// image — with the selected instance outlined.
#ifndef TL_SHARED_DISPLAY_H
#define TL_SHARED_DISPLAY_H
#include "common.h"

TL_BEGIN
TL_CONST uint kDisplaySource = 0;      // sampler2D / usampler2D / sampler3D: what is shown
TL_CONST uint kDisplayInstanceId = 1;  // usampler2D: gbuffer.instanceId, for the outline
TL_CONST uint kDisplayOutput = 2;      // rgba8 storage image: display.ldr
TL_CONST uint kDisplayCompanionA = 3;  // sampler2D: a resource a meaning reads beside the source
TL_CONST uint kDisplayCompanionB = 4;  //   (SH irradiance: A the chroma, B the octahedral normal)

TL_CONST uint kDisplayModeFinal = 0;   // an already display-encoded image: copied
TL_CONST uint kDisplayModeLinear = 1;  // a float resource: (value - min) / (max - min), sRGB-encoded
TL_CONST uint kDisplayModeId = 2;      // an integer resource: a colour per value

// Which channel a float resource shows.
TL_CONST uint kDisplayChannelRgb = 0;
TL_CONST uint kDisplayChannelR = 1;
TL_CONST uint kDisplayChannelG = 2;
TL_CONST uint kDisplayChannelB = 3;
TL_CONST uint kDisplayChannelA = 4;
TL_CONST uint kDisplayChannelLuminance = 5;

TL_CONST uint kDisplayFlagFalseColour = 1u;  // one channel through tlDisplayFalseColour
TL_CONST uint kDisplayFlagHighlight = 2u;    // NaN magenta, infinity yellow, negative blue
TL_CONST uint kDisplayFlagGrid = 4u;         // texel borders (when zoomed in far enough)
TL_CONST uint kDisplayFlagNegativesValid = 8u;  // with Highlight: negatives are data here (normals, SH), not flagged

// What a decoded resource means, shown instead of its stored values (lighting/common/
// decoders.h meaningView): the viewer's default for a resource whose decoder has one.
TL_CONST uint kDisplayMeaningNone = 0;         // the stored values
TL_CONST uint kDisplayMeaningHitDistance = 1;  // r32ui hit record: distance in false colour; miss, pending flat
TL_CONST uint kDisplayMeaningOctNormal = 2;    // rg oct normal (float): the unit vector as colour, n * 0.5 + 0.5
TL_CONST uint kDisplayMeaningHitNormal = 3;    // rg32ui hit surface: its oct snorm16 normal as colour
TL_CONST uint kDisplayMeaningShIrradiance = 4; // L1 SH of luma + chroma (A) at the normal (B): irradiance over the range
TL_CONST uint kDisplayMeaningAo = 5;           // ambient occlusion (r): the visibility as a grey level
// The flat colours of a hit record that is no hit (their legend in the Buffers panel).
TL_FN vec3 tlDisplayMissColour() { return vec3(0.12f, 0.16f, 0.28f); }
TL_FN vec3 tlDisplayPendingColour() { return vec3(0.45f, 0.45f, 0.45f); }

struct DisplayPush {
  vec4 window;        // the part of the source shown: UV offset (xy) and size (zw)
  uint mode;
  uint selectedId;    // instance id + 1 to outline, 0 for none
  uint channels;      // 1..4 channels of the source that carry data
  uint channel;       // kDisplayChannel*
  float rangeMin;     // linear mode: value shown black
  float rangeMax;     // linear mode: value shown white
  uint flags;         // kDisplayFlag*
  float slice;        // 3D sources: w coordinate of the slice shown (0..1)
  uint meaning;       // kDisplayMeaning*
  uint pad0, pad1, pad2;
};

// False colour for t in [0, 1]: dark blue, blue, cyan, green, yellow, red (the legend draws
// the same function).
TL_FN vec3 tlDisplayFalseColour(float t) {
  t = clamp(t, 0.0f, 1.0f) * 5.0f;
  vec3 c0 = vec3(0.05f, 0.03f, 0.25f), c1 = vec3(0.1f, 0.25f, 0.9f), c2 = vec3(0.1f, 0.8f, 0.9f);
  vec3 c3 = vec3(0.2f, 0.85f, 0.2f), c4 = vec3(0.95f, 0.9f, 0.15f), c5 = vec3(0.9f, 0.1f, 0.05f);
  if (t < 1.0f) return mix(c0, c1, t);
  if (t < 2.0f) return mix(c1, c2, t - 1.0f);
  if (t < 3.0f) return mix(c2, c3, t - 2.0f);
  if (t < 4.0f) return mix(c3, c4, t - 3.0f);
  return mix(c4, c5, t - 4.0f);
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::DisplayPush) == 64);
#endif
#endif
