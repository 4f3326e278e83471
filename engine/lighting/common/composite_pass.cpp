#include "lighting/common/composite_pass.h"
#include "lighting/common/taa_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/shadow_pass.h"
#include "shared/brdf_lut.h"

#include <set>

namespace tl::lighting {

using graph::Usage;

void CompositePass::add(graph::RenderGraph& graph, FrameInputs& in, const LightingOutputs& path) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  const auto hdrDesc =
      graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h, "scene-linear radiance before exposure");
  if (!path.radiance.empty()) {
    // The path computed the whole image: pass it through (32-bit float -> half).
    const std::string source = path.radiance;
    graph.addPass(
        "composite", graph::PassKind::Transfer,
        [&](graph::PassBuilder& b) {
          b.read(source, Usage::TransferSrc);
          b.create(kCompositeHdr, hdrDesc, Usage::TransferDst);
        },
        [source](graph::PassContext& ctx) {
          const gpu::Image& src = ctx.image(source);
          const gpu::Image& dst = ctx.image(kCompositeHdr);
          VkImageBlit blit{};
          blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          blit.srcOffsets[1] = {int32_t(src.extent().width), int32_t(src.extent().height), 1};
          blit.dstOffsets[1] = {int32_t(dst.extent().width), int32_t(dst.extent().height), 1};
          vkCmdBlitImage(ctx.cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(),
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        });
    return;
  }
  // Without a sun the shadow map is never sampled (the shader tests kFrameFlagSunShadows):
  // not reading it lets the graph cull the shadow pass.
  const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
  shared::CompositePush push{};
  push.flags = (path.ambientOcclusion.empty() ? 0u : shared::kCompositeHasAo) |
               (path.diffuseShY.empty() || path.diffuseCoCg.empty() ? 0u : shared::kCompositeHasGi) |
               (path.aoOnGi ? shared::kCompositeAoOnGi : 0u);
  const bool far = !path.farShY.empty() && !path.farCoCg.empty() && !path.farAo.empty() &&
                   (push.flags & shared::kCompositeHasGi);
  if (far) push.flags |= shared::kCompositeHasFarGi;
  if (in.settings.specularGi) push.flags |= shared::kCompositeSpecularGi;
  // The light table's radiance (lights.direct); without lights the base colour stands in, unread.
  const std::string lights = path.lightsRadiance.empty() ? std::string("gbuffer.baseColor") : path.lightsRadiance;
  if (!path.lightsRadiance.empty()) push.flags |= shared::kCompositeHasLights;
  push.giBlendDistance = path.giBlendDistance;
  push.openSkyDirectionality = path.openSkyDirectionality;
  push.farOpenSkyDirectionality = path.farOpenSkyDirectionality;
  push.giBlendWidth = kGiBlendWidthFraction * path.giBlendDistance;
  // Absent outputs: the binding still needs an image; the base colour stands in, unread.
  const std::string standIn = "gbuffer.baseColor";
  const bool gi = (push.flags & shared::kCompositeHasGi) != 0;
  const CompositePathInputs inputs{path.ambientOcclusion.empty() ? standIn : path.ambientOcclusion,
                          gi ? path.diffuseShY : standIn,
                          gi ? path.diffuseCoCg : standIn,
                          far ? path.farShY : standIn,
                          far ? path.farCoCg : standIn,
                          far ? path.farAo : standIn};
  // With TAA the composite is this frame's jittered image; the TAA pass resolves it into
  // composite.hdr (lighting/common/taa_pass.h).
  const char* output = in.temporalAntialiasing ? kCompositeUnresolved : kCompositeHdr;
  const auto unresolvedDesc = graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h,
                                                           "scene-linear radiance before exposure, jittered (TAA input)");
  if (pointSampler_.handle() == VK_NULL_HANDLE) {
    pointSampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "composite.point");
    // Outside the shadow map is lit (border white + compare): the fit covers the view.
    shadowSampler_ = gpu::Sampler(in.device, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER,
                                  "composite.shadowCompare", true);
  }
  // Redeferred shading (lighting/common/redeferred_pass.h): the same image from the I-buffer.
  if (in.settings.redeferred) {
    redeferred_.add(graph, in, push, inputs, output, in.temporalAntialiasing ? unresolvedDesc : hdrDesc,
                    pointSampler_.handle(), shadowSampler_.handle());
    addStages(graph, in, push, inputs);
    return;
  }
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
                         {shared::kCompositeOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                         {shared::kCompositeShadowDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kCompositeLights, sampled}};
    for (const auto& b : CompositePathInputs::bindings()) d.layout.bindings.push_back(b);
    d.layout.pushConstantBytes = sizeof(shared::CompositePush);
    pipeline_ = gpu::createComputePipeline(in.device, d);
  }

  graph.addPass(
      "composite", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.baseColor", "gbuffer.normal", "gbuffer.material", "gbuffer.emissive"})
          b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (sun) b.read(kShadowSunDepth, Usage::Sampled);
        if (lights != "gbuffer.baseColor") b.read(lights, Usage::Sampled);
        inputs.declareReads(b, "gbuffer.baseColor");
        b.create(output, in.temporalAntialiasing ? unresolvedDesc : hdrDesc, Usage::StorageWrite);
      },
      [this, &in, sun, push, inputs, output, lights](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        VkSampler point = pointSampler_.handle();
        // The binding must still hold a depth image; the G-buffer's depth stands in, unread.
        const gpu::Image& shadow = ctx.image(sun ? kShadowSunDepth : kGbufferDepth);
        ctx.bind(pipeline_);
        ctx.descriptors()
            .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kCompositeBaseColor, ctx.image("gbuffer.baseColor").view(), point, ro)
            .sampledImage(shared::kCompositeNormal, ctx.image("gbuffer.normal").view(), point, ro)
            .sampledImage(shared::kCompositeMaterial, ctx.image("gbuffer.material").view(), point, ro)
            .sampledImage(shared::kCompositeEmissive, ctx.image("gbuffer.emissive").view(), point, ro)
            .sampledImage(shared::kCompositeDepth, ctx.image(kGbufferDepth).view(), point, ro)
            .sampledImage(shared::kCompositeShadow, shadow.view(), shadowSampler_.handle(), ro)
            .storageImage(shared::kCompositeOutput, ctx.image(output).view())
            .sampledImage(shared::kCompositeShadowDepth, shadow.view(), point, ro)
            .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle())
            .sampledImage(shared::kCompositeLights, ctx.image(lights).view(), point, ro);
        inputs.bind(ctx, point);
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  addStages(graph, in, push, inputs);
}

std::vector<gpu::Binding> CompositePathInputs::bindings() {
  const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  return {{shared::kCompositeAo, sampled},     {shared::kCompositeShY, sampled},
          {shared::kCompositeCoCg, sampled},   {shared::kCompositeFarShY, sampled},
          {shared::kCompositeFarCoCg, sampled}, {shared::kCompositeFarAo, sampled}};
}

void CompositePathInputs::declareReads(graph::PassBuilder& b, const std::string& alreadyRead) const {
  // The stand-in may fill several bindings: a set reads it once.
  for (const std::string& n : std::set<std::string>{ao, shY, coCg, farShY, farCoCg, farAo})
    if (n != alreadyRead) b.read(n, Usage::Sampled);
}

void CompositePathInputs::bind(graph::PassContext& ctx, VkSampler sampler) const {
  const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
  ctx.descriptors()
      .sampledImage(shared::kCompositeAo, ctx.image(ao).view(), sampler, ro)
      .sampledImage(shared::kCompositeShY, ctx.image(shY).view(), sampler, ro)
      .sampledImage(shared::kCompositeCoCg, ctx.image(coCg).view(), sampler, ro)
      .sampledImage(shared::kCompositeFarShY, ctx.image(farShY).view(), sampler, ro)
      .sampledImage(shared::kCompositeFarCoCg, ctx.image(farCoCg).view(), sampler, ro)
      .sampledImage(shared::kCompositeFarAo, ctx.image(farAo).view(), sampler, ro);
}

void CompositePass::addStages(graph::RenderGraph& graph, FrameInputs& in, const shared::CompositePush& push,
                              const CompositePathInputs& inputs) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!stagesPipeline_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "composite.stages";
    d.shader = "common/composite_stages.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kCompositeBaseColor, sampled},
                         {shared::kCompositeNormal, sampled},
                         {shared::kCompositeMaterial, sampled},
                         {shared::kCompositeDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kCompositeStageAo, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                         {shared::kCompositeStageIrradiance, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    for (const auto& b : CompositePathInputs::bindings()) d.layout.bindings.push_back(b);
    d.layout.pushConstantBytes = sizeof(shared::CompositePush);
    stagesPipeline_ = gpu::createComputePipeline(in.device, d);
  }
  graph.addPass(
      "composite.stages", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        for (const char* n : {"gbuffer.baseColor", "gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        inputs.declareReads(b, "gbuffer.baseColor");
        b.create(kCompositeAo,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16_SFLOAT, w, h, "the AO the composite applied (0: sky)").decodedAs("ao"),
                 Usage::StorageWrite);
        b.create(kCompositeIrradiance,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              "the diffuse irradiance the composite used: sky + bounce, no sun (0: sky)"),
                 Usage::StorageWrite);
      },
      [this, &in, push, inputs](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        VkSampler point = pointSampler_.handle();
        ctx.bind(stagesPipeline_);
        ctx.descriptors()
            .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kCompositeBaseColor, ctx.image("gbuffer.baseColor").view(), point, ro)
            .sampledImage(shared::kCompositeNormal, ctx.image("gbuffer.normal").view(), point, ro)
            .sampledImage(shared::kCompositeMaterial, ctx.image("gbuffer.material").view(), point, ro)
            .sampledImage(shared::kCompositeDepth, ctx.image(kGbufferDepth).view(), point, ro)
            .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle())
            .storageImage(shared::kCompositeStageAo, ctx.image(kCompositeAo).view())
            .storageImage(shared::kCompositeStageIrradiance, ctx.image(kCompositeIrradiance).view());
        inputs.bind(ctx, point);
        ctx.pushConstants(push);
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
                 graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "display image: exposure, ACES, sRGB").displayReferred(),
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
