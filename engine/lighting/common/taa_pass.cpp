#include "lighting/common/taa_pass.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"
#include "shared/frame.h"
#include "shared/taa.h"

namespace tl::lighting {

// The resolved image is reprojected along the motion vectors, which span one frame: it is
// kept across camera motion and any change of the light (neighbourhood clipping follows it),
// restarted by a cut, a new scene or a frame it did not see.
constexpr HistoryPolicy kTaaHistory{"taa", parts(FramePart::Scene, FramePart::CameraCut, FramePart::FrameGap), 0};

void TaaPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  const uint32_t w = in.settings.width, h = in.settings.height;
  const auto hdr = [&](const char* what) { return in.screenImage(kCompositeHdrFormat, what); };
  const std::string historyName = taaHistoryName(in.pathName);
  const graph::ImageName history{historyName};
  ComputePass pass(in.device, "taa", "common/taa.comp");
  pass.history(shared::kTaaBindingHistory, history, hdr("TAA: this path's last resolved image"), graph, in,
               keepers_[in.pathName], kTaaHistory, samplers::linear);
  shared::TaaPush push{};
  push.blend = std::clamp(in.settings.taaBlend, 0.01f, 1.0f);
  push.historyValid = pass.historyValid() ? 1u : 0u;
  pass.uniform(shared::kTaaBindingFrame, kFrameConstants)
      .sampled(shared::kTaaBindingCurrent, kCompositeUnresolved, samplers::point)
      .sampled(shared::kTaaBindingMotion, gbuffer::kMotion, samplers::point)
      .storageOut(shared::kTaaBindingOutput, kCompositeHdr, hdr("scene-linear radiance before exposure, resolved by TAA"))
      .push(push)
      .dispatch(w, h)
      .add(graph);
  addCopyPass(graph, "taa.history.store", {{kCompositeHdr, history}});
}

}  // namespace tl::lighting
