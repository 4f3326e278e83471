#include "lighting/common/compare_view_pass.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/display_pass.h"
#include "lighting/common/pass_builders.h"
#include "shared/compare_view.h"

#include <set>

namespace tl::lighting {

std::string compareImageName(const std::string& path) { return "compare." + path; }

void CompareViewPass::add(graph::RenderGraph& graph, FrameInputs& in, const CompareViewRequest& request,
                          const std::string& rendered, bool haveLeft, bool haveRight) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  const auto desc = in.screenImage(kCompositeHdrFormat, "a compared path's last image (scene-linear radiance)");
  const std::string left = compareImageName(request.left), right = compareImageName(request.right),
                    mine = compareImageName(rendered);
  for (const std::string& n : std::set<std::string>{left, right, mine}) graph.declareCache(n, desc);
  addCopyPass(graph, "compare.keep", {{kCompositeHdr, graph::ImageName{mine}}});

  shared::CompareViewPush push{};
  push.wipe = std::clamp(request.wipe, 0.0f, 1.0f);
  push.mode = request.difference ? shared::kCompareViewDifference : shared::kCompareViewWipe;
  push.differenceScale = request.differenceScale;
  push.flags = (haveLeft ? shared::kCompareViewLeftValid : 0u) | (haveRight ? shared::kCompareViewRightValid : 0u);
  ComputePass(in.device, "compare.view", "common/compare_view.comp")
      .uniform(shared::kCompareViewFrame, kFrameConstants)
      .sampled(shared::kCompareViewLeft, graph::ImageName{left})
      .sampled(shared::kCompareViewRight, graph::ImageName{right})
      .storageOut(shared::kCompareViewOutput, kDisplayLdr,
                  in.screenImage(VK_FORMAT_R8G8B8A8_UNORM, "compare view: wipe or difference").displayReferred())
      .push(push)
      .dispatch(w, h)
      .add(graph);
  graph.markOutput(kDisplayLdr);
}

}  // namespace tl::lighting
