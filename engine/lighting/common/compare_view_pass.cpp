#include "lighting/common/compare_view_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/display_pass.h"
#include "shared/compare_view.h"

#include <set>

namespace tl::lighting {

std::string compareImageName(const std::string& path) { return "compare." + path; }

void CompareViewPass::add(graph::RenderGraph& graph, FrameInputs& in, const CompareViewRequest& request,
                          const std::string& rendered, bool haveLeft, bool haveRight) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!pipeline_) {
    gpu::ComputePipelineDesc d;
    d.name = "compare.view";
    d.shader = "common/compare_view.comp";
    d.layout.bindings = {{shared::kCompareViewFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kCompareViewLeft, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                         {shared::kCompareViewRight, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                         {shared::kCompareViewOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    d.layout.pushConstantBytes = sizeof(shared::CompareViewPush);
    pipeline_ = gpu::createComputePipeline(in.device, d);
    sampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "compare.point");
  }
  const auto desc = graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h,
                                                 "a compared path's last image (scene-linear radiance)");
  const std::string left = compareImageName(request.left), right = compareImageName(request.right),
                    mine = compareImageName(rendered);
  for (const std::string& n : std::set<std::string>{left, right, mine}) graph.declareCache(n, desc);
  addCopyPass(graph, "compare.keep", {{kCompositeHdr, mine}});

  shared::CompareViewPush push{};
  push.wipe = std::clamp(request.wipe, 0.0f, 1.0f);
  push.mode = request.difference ? shared::kCompareViewDifference : shared::kCompareViewWipe;
  push.differenceScale = request.differenceScale;
  push.flags = (haveLeft ? shared::kCompareViewLeftValid : 0u) | (haveRight ? shared::kCompareViewRightValid : 0u);
  graph.addPass(
      "compare.view", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, graph::Usage::StorageRead);
        for (const std::string& n : std::set<std::string>{left, right}) b.read(n, graph::Usage::Sampled);
        b.create(kDisplayLdr, graph::ResourceDesc::image2D(VK_FORMAT_R8G8B8A8_UNORM, w, h, "compare view: wipe or difference").displayReferred(),
                 graph::Usage::StorageWrite);
      },
      [this, &in, push, left, right](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        ctx.bind(pipeline_);
        ctx.descriptors()
            .uniformBuffer(shared::kCompareViewFrame, in.constantsBuffer.handle())
            .sampledImage(shared::kCompareViewLeft, ctx.image(left).view(), sampler_.handle(), ro)
            .sampledImage(shared::kCompareViewRight, ctx.image(right).view(), sampler_.handle(), ro)
            .storageImage(shared::kCompareViewOutput, ctx.image(kDisplayLdr).view());
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  graph.markOutput(kDisplayLdr);
}

}  // namespace tl::lighting
