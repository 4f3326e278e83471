#include "lighting/common/composite_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/shadow_pass.h"

namespace tl::lighting {

using graph::Usage;

void CompositePass::add(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path) {
  (void)path;  // the direct path produces none of the optional inputs; legacy/RT wire them here
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!pipeline_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "composite";
    d.shader = "common/composite.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kCompositeBaseColor, sampled},
                         {shared::kCompositeNormal, sampled},
                         {shared::kCompositeMaterial, sampled},
                         {shared::kCompositeEmissive, sampled},
                         {shared::kCompositeDepth, sampled},
                         {shared::kCompositeShadow, sampled},
                         {shared::kCompositeOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    pipeline_ = gpu::createComputePipeline(in.device, d);
    pointSampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "composite.point");
    // Outside the shadow map is lit (border white + compare): the fit covers the view.
    shadowSampler_ = gpu::Sampler(in.device, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER,
                                  "composite.shadowCompare", true);
  }

  graph.addPass(
      "composite", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        for (const char* n : {"gbuffer.baseColor", "gbuffer.normal", "gbuffer.material", "gbuffer.emissive"})
          b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        b.read(kShadowSunDepth, Usage::Sampled);
        b.create(kCompositeHdr,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h, "scene-linear radiance before exposure"),
                 Usage::StorageWrite);
      },
      [this, &in](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        VkSampler point = pointSampler_.handle();
        ctx.bind(pipeline_);
        ctx.descriptors()
            .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kCompositeBaseColor, ctx.image("gbuffer.baseColor").view(), point, ro)
            .sampledImage(shared::kCompositeNormal, ctx.image("gbuffer.normal").view(), point, ro)
            .sampledImage(shared::kCompositeMaterial, ctx.image("gbuffer.material").view(), point, ro)
            .sampledImage(shared::kCompositeEmissive, ctx.image("gbuffer.emissive").view(), point, ro)
            .sampledImage(shared::kCompositeDepth, ctx.image(kGbufferDepth).view(), point, ro)
            .sampledImage(shared::kCompositeShadow, ctx.image(kShadowSunDepth).view(), shadowSampler_.handle(), ro)
            .storageImage(shared::kCompositeOutput, ctx.image(kCompositeHdr).view());
        ctx.dispatch(in.settings.width, in.settings.height);
      });
}

void TonemapPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!pipeline_) {
    gpu::ComputePipelineDesc d;
    d.name = "tonemap";
    d.shader = "common/tonemap.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kTonemapInput, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                         {shared::kTonemapOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    pipeline_ = gpu::createComputePipeline(in.device, d);
    pointSampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "tonemap.point");
  }
  graph.addPass(
      "tonemap", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kCompositeHdr, Usage::Sampled);
        b.create(kTonemapLdr,
                 graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "display image: exposure, ACES, sRGB"),
                 Usage::StorageWrite);
      },
      [this, &in](graph::PassContext& ctx) {
        ctx.bind(pipeline_);
        ctx.descriptors()
            .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kTonemapInput, ctx.image(kCompositeHdr).view(), pointSampler_.handle(),
                          VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL)
            .storageImage(shared::kTonemapOutput, ctx.image(kTonemapLdr).view());
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  graph.markOutput(kTonemapLdr);
  graph.markOutput(kCompositeHdr);
}

}  // namespace tl::lighting
