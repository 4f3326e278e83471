// Sun shadow map: depth of every instance seen from the sun through the orthographic
// projection the session fitted to the view (FrameConstants::sunViewProj).
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

namespace tl::lighting {

inline constexpr const char* kShadowSunDepth = "shadow.sunDepth";  // D32F, standard Z (0 near the sun)

class ShadowPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);

 private:
  gpu::Pipeline pipeline_;
  gpu::Pipeline maskedPipeline_;  // alpha MASK casters: discards where the texture cuts them out
};

}  // namespace tl::lighting
