#include "lighting/common/taa_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "shared/frame.h"
#include "shared/taa.h"

namespace tl::lighting {

using graph::Usage;

// The resolved image is reprojected along the motion vectors, which span one frame: it is
// kept across camera motion and any change of the light (neighbourhood clipping follows it),
// restarted by a cut, a new scene or a frame it did not see.
constexpr HistoryPolicy kTaaHistory{"taa", parts(FramePart::Scene, FramePart::CameraCut, FramePart::FrameGap), 0};

void TaaPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!pipeline_) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = "taa";
    d.shader = "common/taa.comp";
    d.layout.bindings = {{shared::kTaaBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kTaaBindingCurrent, sampled},
                         {shared::kTaaBindingHistory, sampled},
                         {shared::kTaaBindingMotion, sampled},
                         {shared::kTaaBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    d.layout.pushConstantBytes = sizeof(shared::TaaPush);
    pipeline_ = gpu::createComputePipeline(in.device, d);
    pointSampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "taa.point");
    linearSampler_ = gpu::Sampler(in.device, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "taa.linear");
  }
  const auto hdr = [&](const char* what) { return graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h, what); };
  const std::string history = taaHistoryName(in.pathName);
  const graph::ResourceDesc historyDesc = hdr("TAA: this path's last resolved image");
  const bool stored = in.executor.historyValid(history, historyDesc);
  const bool kept =
      keepers_[in.pathName].advance(kTaaHistory, in.key, in.pathName, in.historyLog, {stored}).action != HistoryAction::Restart;
  graph.declarePersistent(history, historyDesc);
  graph.addPass(
      "taa", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kCompositeUnresolved, Usage::Sampled);
        b.read(history, Usage::Sampled);
        b.read("gbuffer.motion", Usage::Sampled);
        b.create(kCompositeHdr, hdr("scene-linear radiance before exposure, resolved by TAA"), Usage::StorageWrite);
      },
      [this, &in, history, kept](graph::PassContext& ctx) {
        shared::TaaPush push{};
        push.blend = std::clamp(in.settings.taaBlend, 0.01f, 1.0f);
        push.historyValid = kept && ctx.historyValid(history) ? 1u : 0u;
        ctx.bind(pipeline_);
        ctx.pushConstants(push);
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.descriptors()
            .uniformBuffer(shared::kTaaBindingFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kTaaBindingCurrent, ctx.image(kCompositeUnresolved).view(), pointSampler_.handle(), ro)
            .sampledImage(shared::kTaaBindingHistory, ctx.image(history).view(), linearSampler_.handle(), ro)
            .sampledImage(shared::kTaaBindingMotion, ctx.image("gbuffer.motion").view(), pointSampler_.handle(), ro)
            .storageImage(shared::kTaaBindingOutput, ctx.image(kCompositeHdr).view());
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  addCopyPass(graph, "taa.history.store", {{kCompositeHdr, history}});
}

}  // namespace tl::lighting
