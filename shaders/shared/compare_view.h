// The editor's compare view (engine/lighting/common/compare_view_pass.cpp): two lighting
// paths' last images side by side with a wipe, or their difference, in display.ldr.
#ifndef TL_SHARED_COMPARE_VIEW_H
#define TL_SHARED_COMPARE_VIEW_H
#include "common.h"

TL_BEGIN
TL_CONST uint kCompareViewFrame = 0;   // FrameConstants (exposure)
TL_CONST uint kCompareViewLeft = 1;    // sampler2D: scene-linear radiance of the left side
TL_CONST uint kCompareViewRight = 2;   // sampler2D: the right side
TL_CONST uint kCompareViewOutput = 3;  // rgba8 storage image: display.ldr

TL_CONST uint kCompareViewWipe = 0;        // left of the wipe: left image; right of it: right image
TL_CONST uint kCompareViewDifference = 1;  // |left - right| of the display images, in false colour

TL_CONST uint kCompareViewLeftValid = 1u;   // the side has an image yet (else drawn dark grey)
TL_CONST uint kCompareViewRightValid = 2u;

struct CompareViewPush {
  float wipe;             // 0..1 of the width
  uint mode;              // kCompareView*
  float differenceScale;  // difference mode: display-value difference shown at the top of the ramp = 1 / scale
  uint flags;             // kCompareView*Valid
};
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::CompareViewPush) == 16);
#endif
#endif
