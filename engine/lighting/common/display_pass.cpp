#include "lighting/common/display_pass.h"

#include "gpu/formats.h"
#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "shared/display.h"

namespace tl::lighting {

void DisplayPass::add(graph::RenderGraph& graph, FrameInputs& in, const DisplayRequest& request) {
  if (!floatPipeline_) {
    auto make = [&](const char* name, const char* shader) {
      gpu::ComputePipelineDesc d;
      d.name = name;
      d.shader = shader;
      d.layout.bindings = {{shared::kDisplaySource, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kDisplayInstanceId, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kDisplayOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
      d.layout.pushConstantBytes = sizeof(shared::DisplayPush);
      return gpu::createComputePipeline(in.device, d);
    };
    floatPipeline_ = make("display.float", "common/display_float.comp");
    uintPipeline_ = make("display.uint", "common/display_uint.comp");
    sampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "display.point");
  }
  const std::string source = request.source.empty() ? kTonemapLdr : request.source;
  auto id = graph.find(source);
  if (!id || graph.resources()[*id].desc.type != graph::ResourceType::Image || graph.resources()[*id].desc.extent.depth > 1)
    throw gpu::Error("the display can show 2D images of the frame; `" + source + "` is not one");
  const VkFormat format = graph.resources()[*id].desc.format;
  const gpu::FormatInfo fi = gpu::formatInfo(format);
  shared::DisplayPush push{};
  push.mode = source == kTonemapLdr ? shared::kDisplayModeFinal
              : fi.kind == gpu::TexelKind::Uint ? shared::kDisplayModeId
                                                 : shared::kDisplayModeLinear;
  push.selectedId = request.selectedInstance;
  push.channels = fi.channels;
  push.scale = request.scale;
  const uint32_t w = in.settings.width, h = in.settings.height;

  graph.addPass(
      "display", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(source, graph::Usage::Sampled);
        if (source != kGbufferChannels[5].name) b.read(kGbufferChannels[5].name, graph::Usage::Sampled);
        b.create(kDisplayLdr, graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "editor viewport image"),
                 graph::Usage::StorageWrite);
      },
      [this, push, source](graph::PassContext& ctx) {
        const gpu::Pipeline& p = push.mode == shared::kDisplayModeId ? uintPipeline_ : floatPipeline_;
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(p);
        ctx.pushConstants(push);
        ctx.descriptors()
            .sampledImage(shared::kDisplaySource, ctx.image(source).view(), sampler_.handle(), ro)
            .sampledImage(shared::kDisplayInstanceId, ctx.image(kGbufferChannels[5].name).view(), sampler_.handle(), ro)
            .storageImage(shared::kDisplayOutput, ctx.image(kDisplayLdr).view());
        ctx.dispatch(ctx.extent(kDisplayLdr).width, ctx.extent(kDisplayLdr).height);
      });
  graph.markOutput(kDisplayLdr);
}

}  // namespace tl::lighting
