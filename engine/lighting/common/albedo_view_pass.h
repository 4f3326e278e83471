// Debug views of the per-instance albedo (engine/albedo/), as named resources any viewer can show:
//   albedo.instance    the resolved albedo the RT path's rays read, per visible pixel; alpha
//                      the source (shared/albedo.h kAlbedoSource*)
//   albedo.difference  |resolved - the G-buffer's hit albedo| (a bake or override vs texels)
//   albedo.impact      |this frame - the frame before the albedo edits|: what they did to GI
// Nothing reads them but a viewer or a capture, so a frame that shows none of them culls
// these passes and pays nothing.
#pragma once

#include "gpu/pipeline.h"
#include "gpu/upload_ring.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

namespace tl::lighting {

inline constexpr graph::ImageName kAlbedoInstance{"albedo.instance"};
inline constexpr graph::ImageName kAlbedoDifference{"albedo.difference"};
inline constexpr graph::ImageName kAlbedoImpact{"albedo.impact"};
inline constexpr graph::BufferName kAlbedoPerInstance{"albedo.perInstance"};
inline constexpr graph::ImageName kAlbedoImpactBaseline{"albedo.impactBaseline"};

class AlbedoViewPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);
  // The next frame's final image becomes the baseline albedo.impact compares against.
  void captureBaseline() { captureBaseline_ = true; }
  bool hasBaseline() const { return haveBaseline_; }

 private:
  gpu::UploadRing perInstance_;
  uint64_t uploadedVersion_ = ~0ull;
  uint64_t sceneId_ = 0;
  bool captureBaseline_ = false, haveBaseline_ = false;
};

}  // namespace tl::lighting
