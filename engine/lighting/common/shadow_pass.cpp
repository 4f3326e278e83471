#include "lighting/common/shadow_pass.h"

#include "graph/executor.h"
#include "shared/scene.h"

namespace tl::lighting {

void createCasterPipelines(FrameInputs& in, gpu::PipelineLayoutDesc layout, const std::string& name,
                           const char* vertexShader, const char* maskedVertexShader, gpu::Pipeline& opaque,
                           gpu::Pipeline& masked) {
  gpu::GraphicsPipelineDesc d;
  d.name = name;
  d.vertexShader = vertexShader;
  d.layout = std::move(layout);
  d.layout.extraSets = {in.scene.table().layout()};
  d.depthFormat = VK_FORMAT_D32_SFLOAT;
  d.vertexBindings = scene::GpuScene::vertexBindings();
  for (const auto& a : scene::GpuScene::vertexAttributes())
    if (a.location == shared::kAttrPosition) d.vertexAttributes.push_back(a);
  d.cullMode = VK_CULL_MODE_NONE;
  d.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
  d.depthBias = true;
  d.depthClamp = true;
  opaque = gpu::createGraphicsPipeline(in.device, d);
  d.name = name + ".masked";
  d.vertexShader = maskedVertexShader;
  d.fragmentShader = "common/shadow_masked.frag";
  d.vertexAttributes.clear();
  for (const auto& a : scene::GpuScene::vertexAttributes())
    if (a.location != shared::kAttrNormal && a.location != shared::kAttrTangent) d.vertexAttributes.push_back(a);
  masked = gpu::createGraphicsPipeline(in.device, d);
}

void ShadowPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t size = in.settings.shadowMapSize;
  if (!pipeline_) {
    gpu::PipelineLayoutDesc layout;
    layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
    createCasterPipelines(in, layout, "shadow.sun", "common/shadow.vert", "common/shadow_masked.vert", pipeline_,
                          maskedPipeline_);
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
