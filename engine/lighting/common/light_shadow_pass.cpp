#include "lighting/common/light_shadow_pass.h"

#include "graph/executor.h"
#include "lighting/common/shadow_pass.h"
#include "shared/lights.h"
#include "shared/scene.h"

#include <fmt/format.h>

namespace tl::lighting {

void LightShadowPass::add(graph::RenderGraph& graph, FrameInputs& in, const LightShadowPlan& plan) {
  if (plan.views.empty()) return;
  if (!pipeline_) {
    gpu::PipelineLayoutDesc layout;
    layout.bindings = {{shared::kBindingLightShadowViews, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    layout.pushConstantBytes = sizeof(shared::LightShadowPush);
    createCasterPipelines(in, layout, "shadow.lights", "common/light_shadow.vert", "common/light_shadow_masked.vert",
                          pipeline_, maskedPipeline_);
  }

  const uint32_t tile = plan.tileTexels, columns = plan.columns, views = uint32_t(plan.views.size());
  graph.addPass(
      "shadow.lights", graph::PassKind::Raster,
      [&](graph::PassBuilder& b) {
        readSceneInputs(b, graph::Usage::VertexOrIndex, false);
        b.read(kLightShadowViews, graph::Usage::StorageRead);
        b.create(kLightShadowAtlas,
                 graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, plan.atlasWidth(), plan.atlasHeight(),
                                              fmt::format("point and spot light shadow maps: {} perspective view(s) of {}^2", views, tile)),
                 graph::Usage::DepthAttachment);
      },
      [this, &in, tile, columns, views](graph::PassContext& ctx) {
        ctx.beginRendering({}, graph::Attachment{kLightShadowAtlas, {}, 1.0f});
        const auto draw = [&](const gpu::Pipeline& p, const auto& instances) {
          if (instances.empty()) return;
          ctx.bind(p);
          ctx.descriptors().storageBuffer(shared::kBindingLightShadowViews, ctx.buffer(kLightShadowViews).handle());
          ctx.flushDescriptors();
          in.scene.table().bind(ctx.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout(), shared::kSceneSet);
          // Slope-scaled bias against acne where the light grazes a surface.
          vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
          for (uint32_t v = 0; v < views; ++v) {
            ctx.setViewport((v % columns) * tile, (v / columns) * tile, tile, tile);
            ctx.pushConstants(shared::LightShadowPush{v, 0, 0, 0});
            in.scene.drawInstances(ctx.cmd, instances);
          }
        };
        draw(pipeline_, in.scene.opaqueInstances());
        draw(maskedPipeline_, in.scene.alphaTestedInstances());
        ctx.endRendering();
      });
}

}  // namespace tl::lighting
