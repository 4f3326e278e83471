#include "lighting/common/display_pass.h"

#include "gpu/formats.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"
#include "shared/display.h"

#include <fmt/format.h>

namespace tl::lighting {

void DisplayPass::add(graph::RenderGraph& graph, FrameInputs& in, const DisplayRequest& request) {
  add(graph, in.device, in.settings.width, in.settings.height, request);
}

void DisplayPass::add(graph::RenderGraph& graph, gpu::Device& device, uint32_t w, uint32_t h, const DisplayRequest& request) {
  const std::string requested = request.source.empty() ? std::string(kTonemapLdr) : request.source;
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
  if (request.keepCopy) addCopyPass(graph, "display.keepCopy", {{graph::ImageName{requested}, kDisplayCopy}});
  const std::string source = request.showCopy && haveCopy && !request.keepCopy ? std::string(kDisplayCopy) : requested;

  const gpu::FormatInfo fi = gpu::formatInfo(desc.format);
  const bool volume = desc.extent.depth > 1;
  shared::DisplayPush push{};
  push.mode = requested == kTonemapLdr ? shared::kDisplayModeFinal
              : fi.kind == gpu::TexelKind::Uint ? shared::kDisplayModeId
                                                 : shared::kDisplayModeLinear;
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
  const bool ids = push.mode == shared::kDisplayModeId;
  const char* kind = ids ? (volume ? "uint3d" : "uint") : (volume ? "float3d" : "float");
  ComputePass pass(device, fmt::format("display.{}", kind), fmt::format("common/display_{}.comp", kind));
  // Only the 2D float view declares the companions; the integer and the volume views have none
  // (the builder refuses a binding the shader does not declare).
  if (!ids && !volume)
    pass.sampled(shared::kDisplayCompanionA, graph::ImageName{companions[0]})
        .sampled(shared::kDisplayCompanionB, graph::ImageName{companions[1]});
  pass.sampled(shared::kDisplaySource, graph::ImageName{source})
      .sampled(shared::kDisplayInstanceId, kGbufferChannels[5].name)
      .storageOut(shared::kDisplayOutput, kDisplayLdr,
                  graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "editor viewport image").displayReferred())
      .push(push)
      .dispatch(w, h)
      .add(graph);
  graph.markOutput(kDisplayLdr);
}

}  // namespace tl::lighting
