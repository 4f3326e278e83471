#include "lighting/common/shadow_pass.h"

#include "graph/executor.h"
#include "shared/scene.h"

namespace tl::lighting {

void ShadowPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t size = in.settings.shadowMapSize;
  if (!pipeline_) {
    gpu::GraphicsPipelineDesc d;
    d.name = "shadow.sun";
    d.vertexShader = "common/shadow.vert";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
    d.layout.extraSets = {in.scene.table().layout()};
    d.depthFormat = VK_FORMAT_D32_SFLOAT;
    d.vertexBindings = scene::GpuScene::vertexBindings();
    // The depth-only vertex shader reads positions alone (other attributes would be fetched
    // for nothing: a performance warning of the validation layers).
    for (const auto& a : scene::GpuScene::vertexAttributes())
      if (a.location == shared::kAttrPosition) d.vertexAttributes.push_back(a);
    d.cullMode = VK_CULL_MODE_NONE;  // thin and single-sided casters must cast from both sides
    d.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    d.depthBias = true;
    d.depthClamp = true;  // casters between the sun and the near plane clamp to it instead of vanishing
    pipeline_ = gpu::createGraphicsPipeline(in.device, d);
    // Cut-out materials (alpha MASK) need their texture's alpha: a fragment stage that
    // discards, only for the instances that have one, so opaque casters keep the depth-only path.
    d.name = "shadow.sun.masked";
    d.vertexShader = "common/shadow_masked.vert";
    d.fragmentShader = "common/shadow_masked.frag";
    d.vertexAttributes.clear();
    for (const auto& a : scene::GpuScene::vertexAttributes())
      if (a.location != shared::kAttrNormal && a.location != shared::kAttrTangent) d.vertexAttributes.push_back(a);
    maskedPipeline_ = gpu::createGraphicsPipeline(in.device, d);
  }

  graph.addPass(
      "shadow.sun", graph::PassKind::Raster,
      [&](graph::PassBuilder& b) {
        readSceneInputs(b, graph::Usage::VertexOrIndex, false);
        b.create(kShadowSunDepth,
                 graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, size, size, "sun shadow map depth, orthographic"),
                 graph::Usage::DepthAttachment);
      },
      [this, &in](graph::PassContext& ctx) {
        ctx.beginRendering({}, graph::Attachment{kShadowSunDepth, {}, 1.0f});
        ctx.bind(pipeline_);
        ctx.descriptors().uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle());
        ctx.flushDescriptors();
        in.scene.table().bind(ctx.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout(), shared::kSceneSet);
        // Slope-scaled bias against acne on surfaces at grazing angles to the sun.
        vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
        in.scene.drawInstances(ctx.cmd, in.scene.opaqueInstances());
        if (!in.scene.alphaTestedInstances().empty()) {
          ctx.bind(maskedPipeline_);
          ctx.descriptors().uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle());
          ctx.flushDescriptors();
          in.scene.table().bind(ctx.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, maskedPipeline_.layout(), shared::kSceneSet);
          vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
          in.scene.drawInstances(ctx.cmd, in.scene.alphaTestedInstances());
        }
        ctx.endRendering();
      });
}

}  // namespace tl::lighting
