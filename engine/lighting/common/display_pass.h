// The editor's display pass: the final image, or any resource of the frame made visible
// (floats scaled and sRGB-encoded, integers as a colour per value), with the selected
// instance outlined. Only the editor adds it; headless renders never pay for it.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <string>

namespace tl::lighting {

inline constexpr const char* kDisplayLdr = "display.ldr";

struct DisplayRequest {
  std::string source;             // a resource of the frame; empty: the final image
  uint32_t selectedInstance = 0;  // instance index + 1 to outline, 0 for none
  float scale = 1.0f;             // multiplier for float resources
};

class DisplayPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in, const DisplayRequest& request);

 private:
  gpu::Pipeline floatPipeline_, uintPipeline_;
  gpu::Sampler sampler_;
};

}  // namespace tl::lighting
