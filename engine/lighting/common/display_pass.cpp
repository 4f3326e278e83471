#include "lighting/common/display_pass.h"

#include "gpu/formats.h"
#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "shared/display.h"

namespace tl::lighting {

void DisplayPass::add(graph::RenderGraph& graph, FrameInputs& in, const DisplayRequest& request) {
  add(graph, in.device, in.settings.width, in.settings.height, request);
}

void DisplayPass::add(graph::RenderGraph& graph, gpu::Device& device, uint32_t w, uint32_t h, const DisplayRequest& request) {
  if (!floatPipeline_) {
    auto make = [&](const char* name, const char* shader) {
      gpu::ComputePipelineDesc d;
      d.name = name;
      d.shader = shader;
      d.layout.bindings = {{shared::kDisplaySource, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kDisplayInstanceId, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kDisplayOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                           {shared::kDisplayCompanionA, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kDisplayCompanionB, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}};
      d.layout.pushConstantBytes = sizeof(shared::DisplayPush);
      return gpu::createComputePipeline(device, d);
    };
    floatPipeline_ = make("display.float", "common/display_float.comp");
    float3dPipeline_ = make("display.float3d", "common/display_float3d.comp");
    uintPipeline_ = make("display.uint", "common/display_uint.comp");
    sampler_ = gpu::Sampler(device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "display.point");
  }
  const std::string requested = request.source.empty() ? kTonemapLdr : request.source;
  auto id = graph.find(requested);
  if (!id || graph.resources()[*id].desc.type != graph::ResourceType::Image)
    throw gpu::Error("the display shows images of the frame; `" + requested + "` is not one");
  const graph::ResourceDesc desc = graph.resources()[*id].desc;

  // A/B: keep a copy of the source (a cache resource: written this frame, held after), and
  // show it instead of the live resource on request.
  if (request.keepCopy && gpu::formatInfo(desc.format).kind == gpu::TexelKind::Depth)
    throw gpu::Error("A/B keeps copies of colour images; `" + requested + "` is a depth image");
  if (request.keepCopy) copyDesc_ = desc;
  const bool haveCopy = copyDesc_ && *copyDesc_ == desc;
  if (haveCopy) graph.declareCache(kDisplayCopy, *copyDesc_);
  if (request.keepCopy) addCopyPass(graph, "display.keepCopy", {{requested, kDisplayCopy}});
  const std::string source = request.showCopy && haveCopy && !request.keepCopy ? std::string(kDisplayCopy) : requested;

  const gpu::FormatInfo fi = gpu::formatInfo(desc.format);
  const bool volume = desc.extent.depth > 1;
  shared::DisplayPush push{};
  push.mode = requested == kTonemapLdr ? shared::kDisplayModeFinal
              : fi.kind == gpu::TexelKind::Uint ? shared::kDisplayModeId
                                                 : shared::kDisplayModeLinear;
  if (volume && push.mode == shared::kDisplayModeId)
    throw gpu::Error("the display shows integer images in 2D only; `" + requested + "` is 3D");
  push.selectedId = request.selectedInstance;
  push.channels = fi.channels;
  push.channel = request.channel;
  push.rangeMin = request.rangeMin;
  push.rangeMax = request.rangeMax;
  push.window = request.window;
  push.flags = (request.falseColour ? shared::kDisplayFlagFalseColour : 0u) |
               (request.highlightInvalid ? shared::kDisplayFlagHighlight : 0u) |
               (request.negativesValid ? shared::kDisplayFlagNegativesValid : 0u) | shared::kDisplayFlagGrid;
  push.slice = volume ? (float(std::min(request.slice, desc.extent.depth - 1)) + 0.5f) / float(desc.extent.depth) : 0.0f;
  // A meaning needs its companions as 2D images of the frame; without them, the stored values.
  std::vector<std::string> companions = request.companions;
  bool companionsHere = !volume && source == requested;
  for (const std::string& c : companions) {
    auto cid = graph.find(c);
    companionsHere &= cid && graph.resources()[*cid].desc.type == graph::ResourceType::Image &&
                      graph.resources()[*cid].desc.extent.depth <= 1;
  }
  push.meaning = companionsHere && push.mode != shared::kDisplayModeFinal ? request.meaning : shared::kDisplayMeaningNone;
  if (push.meaning == shared::kDisplayMeaningNone) companions.clear();
  companions.resize(2);  // unused slots show the source (the shader reads them only for a meaning)
  for (std::string& c : companions)
    if (c.empty()) c = source;
  graph.addPass(
      "display", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(source, graph::Usage::Sampled);
        if (source != kGbufferChannels[5].name) b.read(kGbufferChannels[5].name, graph::Usage::Sampled);
        for (size_t i = 0; i < companions.size(); ++i)
          if (companions[i] != source && companions[i] != kGbufferChannels[5].name && (i == 0 || companions[i] != companions[0]))
            b.read(companions[i], graph::Usage::Sampled);
        b.create(kDisplayLdr, graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "editor viewport image").displayReferred(),
                 graph::Usage::StorageWrite);
      },
      [this, push, source, volume, companions](graph::PassContext& ctx) {
        const gpu::Pipeline& p = push.mode == shared::kDisplayModeId ? uintPipeline_ : volume ? float3dPipeline_ : floatPipeline_;
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(p);
        ctx.pushConstants(push);
        ctx.descriptors()
            .sampledImage(shared::kDisplaySource, ctx.image(source).view(), sampler_.handle(), ro)
            .sampledImage(shared::kDisplayInstanceId, ctx.image(kGbufferChannels[5].name).view(), sampler_.handle(), ro)
            .storageImage(shared::kDisplayOutput, ctx.image(kDisplayLdr).view())
            .sampledImage(shared::kDisplayCompanionA, ctx.image(companions[0]).view(), sampler_.handle(), ro)
            .sampledImage(shared::kDisplayCompanionB, ctx.image(companions[1]).view(), sampler_.handle(), ro);
        ctx.dispatch(ctx.extent(kDisplayLdr).width, ctx.extent(kDisplayLdr).height);
      });
  graph.markOutput(kDisplayLdr);
}

}  // namespace tl::lighting
