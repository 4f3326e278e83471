// Sun shadow map: depth of every instance seen from the sun through the orthographic
// projection the session fitted to the view (FrameConstants::sunViewProj).
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

namespace tl::lighting {

inline constexpr const char* kShadowSunDepth = "shadow.sunDepth";  // D32F, standard Z (0 near the sun)

// A shadow map's two caster pipelines, for the sun's and the lamps' maps alike: opaque casters
// depth-only with positions alone (other attributes would be fetched for nothing: a performance
// warning of the validation layers), alpha MASK casters with a fragment stage that discards
// where the texture cuts them out, so opaque casters keep the depth-only path. Both draw
// double-sided (thin and single-sided casters cast from both sides), with depth bias, and clamp
// casters nearer than the near plane to it instead of losing them. `layout` holds the pass's own
// bindings and push constants; the scene table is added.
void createCasterPipelines(FrameInputs& in, gpu::PipelineLayoutDesc layout, const std::string& name,
                           const char* vertexShader, const char* maskedVertexShader, gpu::Pipeline& opaque,
                           gpu::Pipeline& masked);

class ShadowPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);

 private:
  gpu::Pipeline pipeline_;
  gpu::Pipeline maskedPipeline_;  // alpha MASK casters: discards where the texture cuts them out
};

}  // namespace tl::lighting
