// Sun shadow map: depth of every instance seen from the sun through the orthographic
// projection the session fitted to the view (FrameConstants::sunViewProj).
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <array>
#include <string>

namespace tl::lighting {

inline constexpr graph::ImageName kShadowSunDepth{"shadow.sunDepth"};  // D32F, standard Z (0 near the sun)

// A shadow map's two caster pipelines, for the sun's and the lamps' maps alike: opaque casters
// depth-only with positions alone (other attributes would be fetched for nothing: a performance
// warning of the validation layers), alpha MASK casters with a fragment stage that discards
// where the texture cuts them out, so opaque casters keep the depth-only path. Both draw
// double-sided (thin and single-sided casters cast from both sides), with depth bias, and clamp
// casters nearer than the near plane to it instead of losing them. The pass builder (RasterPass)
// gives them their layout and depth format; the second is a variant() of the first's pass.
std::array<gpu::GraphicsPipelineDesc, 2> casterPipelines(const std::string& name, const char* vertexShader,
                                                          const char* maskedVertexShader);

class ShadowPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);
};

}  // namespace tl::lighting
