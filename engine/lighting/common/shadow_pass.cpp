#include "lighting/common/shadow_pass.h"

#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "shared/scene.h"

namespace tl::lighting {

std::array<gpu::GraphicsPipelineDesc, 2> casterPipelines(const std::string& name, const char* vertexShader,
                                                          const char* maskedVertexShader) {
  gpu::GraphicsPipelineDesc d;
  d.name = name;
  d.vertexShader = vertexShader;
  d.vertexBindings = scene::GpuScene::vertexBindings();
  for (const auto& a : scene::GpuScene::vertexAttributes())
    if (a.location == shared::kAttrPosition) d.vertexAttributes.push_back(a);
  d.cullMode = VK_CULL_MODE_NONE;
  d.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
  d.depthBias = true;
  d.depthClamp = true;
  gpu::GraphicsPipelineDesc masked = d;
  masked.name = name + ".masked";
  masked.vertexShader = maskedVertexShader;
  masked.fragmentShader = "common/shadow_masked.frag";
  masked.vertexAttributes.clear();
  for (const auto& a : scene::GpuScene::vertexAttributes())
    if (a.location != shared::kAttrNormal && a.location != shared::kAttrTangent) masked.vertexAttributes.push_back(a);
  return {d, masked};
}

void ShadowPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t size = in.settings.shadowMapSize;
  const auto [opaque, masked] = casterPipelines("shadow.sun", "common/shadow.vert", "common/shadow_masked.vert");
  RasterPass(in.device, "shadow.sun", opaque)
      .variant(masked)
      .uniform(shared::kBindingFrame, kFrameConstants)
      .depthOut(kShadowSunDepth,
                graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, size, size, "sun shadow map depth, orthographic"), 1.0f)
      .drawsScene(in.scene.table(), false)
      .draw([&in](graph::PassContext& ctx, const RasterPass::Use& use) {
        // Slope-scaled bias against acne on surfaces at grazing angles to the sun.
        vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
        in.scene.drawInstances(ctx, in.scene.opaqueInstances());
        if (!in.scene.alphaTestedInstances().empty()) {
          use(1);
          vkCmdSetDepthBias(ctx.cmd, 0.0f, 0.0f, 1.5f);
          in.scene.drawInstances(ctx, in.scene.alphaTestedInstances());
        }
      })
      .add(graph);
}

}  // namespace tl::lighting
