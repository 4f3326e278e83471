// lights.direct: the light table's reflected radiance at every G-buffer pixel (shaders/common/
// lights_shade.glsl), through the shared BRDF, added by the composite. With one ray-query shadow
// ray per light against a top level the path provides (the rt path's), else through the point
// and spot lights' shadow maps when the frame has any (lighting/common/light_shadow_pass.h), else
// unshadowed (only directional lights in the table). Only
// frames with lights (FrameConstants::lightCount > 0) have the pass.
#pragma once

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "shared/lights.h"

#include <map>
#include <string>
#include <vector>

namespace tl::lighting {

inline constexpr graph::ImageName kLightsRadiance{"lights.radiance"};  // RGBA16F, 0 on the sky
// With more lights than every point evaluates (shared/lights.h kLightsLoopMax), each path
// accumulates the noisy estimate in its own persistent "lights.accum.<path>" while the frame
// key's camera, projection, light, scene, geometry and the path's settings stay.

// What a pass that shades the light table binds at kBindingLights: the table, or in frames
// without lights `standIn` (any buffer the pass binds anyway), which the shaders never read
// (lightCount is 0). Such a pass declares b.read(kLightTable) only when in.constants.lightCount > 0.
VkBuffer lightTableOrStandIn(graph::PassContext& ctx, const FrameInputs& in, VkBuffer standIn);

class LightsPass {
 public:
  // Returns the name of what it wrote, or "" when the frame has no lights (no pass then);
  // with the `redeferred` setting the light table's share of the I-buffer, lights.Ldg first.
  // `structures` names the top level (first) and the bottom levels its rays may reach that the
  // frame rewrites; `tlasHandle` is the top level: shadow rays. Empty: shadow maps.
  std::string add(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                  VkAccelerationStructureKHR tlasHandle);
  // Redeferred below full rate (`redeferredRate`): add() shaded the pattern's pixels; this
  // shades the ones ibuffer.upsample marked (ibuffer.refine), into the same lights.L* sums.
  void addIbufferRefine(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                        VkAccelerationStructureKHR tlasHandle);

 private:
  // Redeferred shading (lighting/common/redeferred_pass.h): the light table's share of the
  // I-buffer (lights.Ldg ...) instead of radiance; returns lights.Ldg.
  // `stage`: shared::kIbufferStage* (every pixel, the pattern's, the refined ones).
  std::string addIbuffer(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                         VkAccelerationStructureKHR tlasHandle, uint32_t stage);

  shared::LightsPush ibufferPush_{};  // this frame's pattern run's: the refining run continues its sums
  std::map<std::string, HistoryKeeper, std::less<>> accumulation_;  // per lighting path
};

}  // namespace tl::lighting
