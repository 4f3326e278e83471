// The ao plugin's bindings (set 0) and push constants, shared by ao_debug_path.cpp and
// ao_trace.comp.
#ifndef TL_PLUGIN_AO_DEBUG_H
#define TL_PLUGIN_AO_DEBUG_H
#include "shared/common.h"

TL_BEGIN
// kBindingFrame (shared/frame.h) holds the frame constants.
TL_CONST uint kAoDebugNormal = 1u;   // sampler2D: gbuffer.normal (octahedral)
TL_CONST uint kAoDebugDepth = 2u;    // sampler2D: gbuffer.depth (0: the sky)
TL_CONST uint kAoDebugTlas = 3u;     // the scene's simplified top level (lighting/common/scene_accel.h)
TL_CONST uint kAoDebugHistory = 4u;  // r32f, persistent: the running mean of the visibility
TL_CONST uint kAoDebugOutput = 5u;   // rgba32f: the grey image (visibility in rgb, black sky)

struct AoDebugPush {
  uint rays;       // per pixel this frame
  uint frames;     // samples in the history after this frame (1: it starts over)
  float aoRadius;  // a ray that hits within this distance is occluded (rtAoRadius, resolved)
  uint pad0;
};
TL_END
#endif
