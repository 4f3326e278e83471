#include "lighting/common/light_shadow_pass.h"

#include "graph/executor.h"
#include "shared/lights.h"
#include "shared/scene.h"

#include <fmt/format.h>

namespace tl::lighting {

void LightShadowPass::add(graph::RenderGraph& graph, FrameInputs& in, const LightShadowPlan& plan) {
  if (plan.views.empty()) return;
  if (!pipeline_) {
    gpu::GraphicsPipelineDesc d;
    d.name = "shadow.lights";
    d.vertexShader = "common/light_shadow.vert";
    d.layout.bindings = {{shared::kBindingLightShadowViews, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    d.layout.extraSets = {in.scene.table().layout()};
    d.layout.pushConstantBytes = sizeof(shared::LightShadowPush);
    d.depthFormat = VK_FORMAT_D32_SFLOAT;
    d.vertexBindings = scene::GpuScene::vertexBindings();
    for (const auto& a : scene::GpuScene::vertexAttributes())
      if (a.location == shared::kAttrPosition) d.vertexAttributes.push_back(a);
    d.cullMode = VK_CULL_MODE_NONE;  // thin and single-sided casters cast from both sides
    d.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    d.depthBias = true;
    d.depthClamp = true;  // casters nearer than the near plane clamp to it instead of vanishing
    pipeline_ = gpu::createGraphicsPipeline(in.device, d);
    d.name = "shadow.lights.masked";
    d.vertexShader = "common/light_shadow_masked.vert";
    d.fragmentShader = "common/shadow_masked.frag";
    d.vertexAttributes.clear();
    for (const auto& a : scene::GpuScene::vertexAttributes())
      if (a.location == shared::kAttrPosition || a.location == shared::kAttrUv) d.vertexAttributes.push_back(a);
    maskedPipeline_ = gpu::createGraphicsPipeline(in.device, d);
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
