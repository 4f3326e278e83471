// Temporal anti-aliasing of the final image (shaders/common/taa.comp): the projection is
// jittered by a sub-pixel offset each frame, and an exponential history, reprojected with
// the motion vectors and clipped to the current 3x3 neighbourhood's box in YCoCg (Playdead,
// Karis 2014), accumulates the jittered frames into an anti-aliased one. Shared by C++ and GLSL.
#ifndef TL_SHARED_TAA_H
#define TL_SHARED_TAA_H
#include "common.h"

TL_BEGIN
// Sub-pixel offset of frame i, in pixels within (-0.5, 0.5): the Halton (2, 3) sequence,
// 8 points long (indices 1..8), so a still camera covers the pixel evenly every 8 frames.
TL_CONST uint kTaaJitterLength = 8u;
TL_FN float tlHalton(uint index, uint base) {
  float f = 1.0f, r = 0.0f;
  uint i = index;
  while (i > 0u) {
    f /= float(base);
    r += f * float(i % base);
    i /= base;
  }
  return r;
}
TL_FN vec2 tlTaaJitterPixels(uint frame) {
  uint i = frame % kTaaJitterLength + 1u;
  return vec2(tlHalton(i, 2u), tlHalton(i, 3u)) - vec2(0.5f);
}

// Clip a history colour (YCoCg) towards the centre of the neighbourhood's box until it lies
// inside: keeps its hue direction better than clamping each channel.
TL_FN vec3 tlTaaClipToBox(vec3 history, vec3 boxMin, vec3 boxMax) {
  vec3 centre = 0.5f * (boxMin + boxMax);
  vec3 extent = max(0.5f * (boxMax - boxMin), vec3(1e-6f));
  vec3 offset = history - centre;
  vec3 units = abs(offset / extent);
  float m = max(units.x, max(units.y, units.z));
  return m > 1.0f ? centre + offset / m : history;
}

struct TaaPush {
  float blend;           // weight of the current frame in the exponential history (0.1: ~10 frames)
  uint historyValid;     // 0: no usable history (first frame, resize, reset): output the current frame
  uint pad0, pad1;
};

TL_CONST uint kTaaBindingFrame = 0;     // FrameConstants
TL_CONST uint kTaaBindingCurrent = 1;   // composite.unresolved
TL_CONST uint kTaaBindingHistory = 2;   // taa.history (bilinear)
TL_CONST uint kTaaBindingMotion = 3;    // gbuffer.motion
TL_CONST uint kTaaBindingOutput = 4;    // composite.hdr (rgba32f)
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::TaaPush) == 16);
#endif
#endif
