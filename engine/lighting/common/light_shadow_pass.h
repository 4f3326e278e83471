// shadow.lights: the shadow maps of point and spot lights (lighting/common/light_shadows.h), one
// depth atlas "shadow.lightsDepth" with a tile per view, every caster drawn once per view. Only
// frames whose light table has shadowed lights have the pass, and only paths that read the
// atlas (direct and legacy: lights.direct, the voxelizer) keep it; rt and the reference trace.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/light_shadows.h"

namespace tl::lighting {

class LightShadowPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in, const LightShadowPlan& plan);
};

}  // namespace tl::lighting
