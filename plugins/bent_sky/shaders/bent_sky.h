// The bentsky plugin's bindings (set 0) and push constants, shared by bent_sky_path.cpp and
// bent_sky.comp.
#ifndef TL_PLUGIN_BENT_SKY_H
#define TL_PLUGIN_BENT_SKY_H
#include "shared/common.h"

TL_BEGIN
// kBindingFrame (shared/frame.h) holds the frame constants.
TL_CONST uint kBentSkyNormal = 1u;   // sampler2D: gbuffer.normal (octahedral)
TL_CONST uint kBentSkyDepth = 2u;    // sampler2D: gbuffer.depth (0: the sky)
TL_CONST uint kBentSkyTlas = 3u;     // the rt path's top level
TL_CONST uint kBentSkyHistory = 4u;  // rgba32f, persistent: mean unoccluded direction (xyz, not normalised), visibility (w)
TL_CONST uint kBentSkyShY = 5u;      // rgba16f: irradiance as L1 SH of luma (shared/sh.h)
TL_CONST uint kBentSkyCoCg = 6u;     // rg16f: its chroma
TL_CONST uint kBentSkyAo = 7u;       // r16f: the visibility

struct BentSkyPush {
  uint rays;        // per pixel this frame
  uint frames;      // samples in the history after this frame (1: it starts over)
  float rayLength;  // metres
  uint pad0;
};
TL_END
#endif
