#include "lighting/common/gbuffer_pass.h"

#include "graph/executor.h"
#include "shared/scene.h"

namespace tl::lighting {

void GbufferPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!pipeline_) {
    gpu::GraphicsPipelineDesc d;
    d.name = "gbuffer";
    d.vertexShader = "common/gbuffer.vert";
    d.fragmentShader = "common/gbuffer.frag";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
    d.layout.extraSets = {in.scene.table().layout()};
    for (auto& c : kGbufferChannels) d.colorFormats.push_back(c.format);
    d.depthFormat = VK_FORMAT_D32_SFLOAT;
    d.vertexBindings = scene::GpuScene::vertexBindings();
    d.vertexAttributes = scene::GpuScene::vertexAttributes();
    // Culling off: single-sided walls seen from behind must still occlude and shade
    // (the shader flips the normal of back faces).
    d.cullMode = VK_CULL_MODE_NONE;
    pipeline_ = gpu::createGraphicsPipeline(in.device, d);
  }

  graph.addPass(
      "gbuffer", graph::PassKind::Raster,
      [&](graph::PassBuilder& b) {
        readSceneInputs(b, graph::Usage::VertexOrIndex);
        for (auto& c : kGbufferChannels)
          b.create(c.name, graph::ResourceDesc::image2D(c.format, w, h, c.description).decodedAs(c.decoder).named(c.channels),
                   graph::Usage::ColorAttachment);
        b.create(kGbufferDepth,
                 graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, w, h, "depth, reversed Z (1 near, 0 at infinity)")
                     .named("Z"),  // captures store view depth in metres (session/capture_encoding.h)
                 graph::Usage::DepthAttachment);
      },
      [this, &in](graph::PassContext& ctx) {
        std::vector<graph::Attachment> colors;
        for (auto& c : kGbufferChannels) colors.push_back({c.name, glm::vec4(0.0f), {}});
        ctx.beginRendering(colors, graph::Attachment{kGbufferDepth, {}, 0.0f});
        ctx.bind(pipeline_);
        ctx.descriptors().uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle());
        ctx.flushDescriptors();
        in.scene.table().bind(ctx.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout(), shared::kSceneSet);
        in.scene.drawAll(ctx.cmd);
        ctx.endRendering();
      });
}

}  // namespace tl::lighting
