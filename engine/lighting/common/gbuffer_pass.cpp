#include "lighting/common/gbuffer_pass.h"

#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "shared/gbuffer.h"
#include "shared/scene.h"

namespace tl::lighting {

void GbufferPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  gpu::GraphicsPipelineDesc d;
  d.name = "gbuffer";
  d.vertexShader = "common/gbuffer.vert";
  d.fragmentShader = "common/gbuffer.frag";
  d.vertexBindings = scene::GpuScene::vertexBindings();
  d.vertexAttributes = scene::GpuScene::vertexAttributes();
  // Culling off: the shader culls by the material's doubleSided (one pipeline serves every
  // material, mirrored instances included) and flips the normal of the back faces it keeps.
  d.cullMode = VK_CULL_MODE_NONE;

  RasterPass pass(in.device, "gbuffer", d);
  pass.uniform(shared::kBindingFrame, kFrameConstants);
  pass.optionalBufferIn(shared::kGbufferPreviousPositions, scene::kScenePreviousPositions, in.scene.deforms());
  for (auto& c : kGbufferChannels)
    pass.colorOut(c.name, graph::ResourceDesc::image2D(c.format, w, h, c.description).decodedAs(c.decoder).named(c.channels),
                  glm::vec4(0.0f));
  pass.depthOut(gbuffer::kDepth,
                in.screenImage(VK_FORMAT_D32_SFLOAT, "depth, reversed Z (1 near, 0 at infinity)")
                    .named("Z"),  // captures store view depth in metres (session/capture_encoding.h)
                0.0f)
      .drawsScene(in.scene.table())
      .draw([&in](graph::PassContext& ctx, const RasterPass::Use&) { in.scene.drawAll(ctx); })
      .add(graph);
}

}  // namespace tl::lighting
