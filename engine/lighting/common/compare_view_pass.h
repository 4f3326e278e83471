// The editor's compare view: each compared lighting path keeps its last image as a cache
// resource `compare.<path>` (copied from composite.hdr in the frames it renders), and this
// pass shows two of them in display.ldr, split by a draggable wipe or as their difference.
// Only the editor's Compare panel adds it.
#pragma once

#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <string>

namespace tl::lighting {

// `compare.<path>`: the path's last scene-linear image (RGBA16F, the frame's size).
std::string compareImageName(const std::string& path);

struct CompareViewRequest {
  std::string left, right;  // lighting paths
  float wipe = 0.5f;        // 0..1 of the width
  bool difference = false;  // |left - right| of the display values in false colour
  float differenceScale = 4.0f;  // the ramp's top is a display difference of 1 / scale
};

class CompareViewPass {
 public:
  // `rendered`: the path this frame rendered (its image is copied to compare.<rendered>);
  // `haveLeft`/`haveRight`: whether those sides hold an image from an earlier frame or this one.
  void add(graph::RenderGraph& graph, FrameInputs& in, const CompareViewRequest& request, const std::string& rendered,
           bool haveLeft, bool haveRight);
};

}  // namespace tl::lighting
