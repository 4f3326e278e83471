#include "lighting/common/light_shadow_pass.h"

#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/shadow_pass.h"
#include "shared/lights.h"
#include "shared/scene.h"

#include <fmt/format.h>

namespace tl::lighting {

void LightShadowPass::add(graph::RenderGraph& graph, FrameInputs& in, const LightShadowPlan& plan) {
  if (plan.views.empty()) return;
  const uint32_t tile = plan.tileTexels, columns = plan.columns, views = uint32_t(plan.views.size());
  const auto [opaque, masked] = casterPipelines("shadow.lights", "common/light_shadow.vert", "common/light_shadow_masked.vert");
  RasterPass(in.device, "shadow.lights", opaque)
      .variant(masked)
      .bufferIn(shared::kBindingLightShadowViews, kLightShadowViews)
      .depthOut(kLightShadowAtlas,
                graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, plan.atlasWidth(), plan.atlasHeight(),
                                             fmt::format("point and spot light shadow maps: {} perspective view(s) of {}^2", views, tile)),
                1.0f)
      .drawsScene(in.scene.table(), false)
      .push(shared::LightShadowPush{})  // the view, set per draw
      .draw([&in, tile, columns, views](graph::PassContext& ctx, const RasterPass::Use& use) {
        const auto draw = [&](size_t variant, const auto& instances) {
          if (instances.empty()) return;
          if (variant != 0) use(variant);
          // Slope-scaled bias against acne where the light grazes a surface.
          vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
          for (uint32_t v = 0; v < views; ++v) {
            ctx.setViewport((v % columns) * tile, (v / columns) * tile, tile, tile);
            ctx.pushConstants(shared::LightShadowPush{v, 0, 0, 0});
            in.scene.drawInstances(ctx, instances);
          }
        };
        draw(0, in.scene.opaqueInstances());
        draw(1, in.scene.alphaTestedInstances());
      })
      .add(graph);
}

}  // namespace tl::lighting
