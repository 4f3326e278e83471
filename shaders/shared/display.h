// The editor's display pass (engine/lighting/common/display_pass.cpp): shows the final
// image or any other resource of the frame, with the selected instance outlined.
#ifndef TL_SHARED_DISPLAY_H
#define TL_SHARED_DISPLAY_H
#include "common.h"

TL_BEGIN
TL_CONST uint kDisplaySource = 0;      // sampler2D or usampler2D: what is shown
TL_CONST uint kDisplayInstanceId = 1;  // usampler2D: gbuffer.instanceId, for the outline
TL_CONST uint kDisplayOutput = 2;      // rgba8 storage image: display.ldr

TL_CONST uint kDisplayModeFinal = 0;   // an already display-encoded image: copied
TL_CONST uint kDisplayModeLinear = 1;  // a float resource: |value| * scale, sRGB-encoded
TL_CONST uint kDisplayModeId = 2;      // an integer resource: a colour per value

struct DisplayPush {
  uint mode;
  uint selectedId;    // instance id + 1 to outline, 0 for none
  uint channels;      // 1..4 channels of the source that carry data
  float scale;        // linear mode: multiplier before encoding
};
TL_END
#endif
