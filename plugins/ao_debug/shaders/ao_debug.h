// The ao plugin's bindings (set 0), shared by ao_debug_path.cpp and ao_grey.comp.
#ifndef TL_PLUGIN_AO_DEBUG_H
#define TL_PLUGIN_AO_DEBUG_H
#include "shared/common.h"

TL_BEGIN
TL_CONST uint kAoDebugSource = 0u;  // sampler2D: the rt path's AO (1 = unoccluded), any resolution
TL_CONST uint kAoDebugDepth = 1u;   // sampler2D: gbuffer.depth (0: the sky)
TL_CONST uint kAoDebugOutput = 2u;  // rgba32f storage image: the grey image, full resolution
TL_END
#endif
