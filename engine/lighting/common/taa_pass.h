// Temporal anti-aliasing of the final image (shared/taa.h): the composite, rendered with a
// jittered projection, goes in as composite.unresolved; the resolved image comes out as
// composite.hdr, the name everything downstream (tonemap, captures, compare, the paths'
// screen feedback) already reads. Its history is the graph's persistent taa.history.
#pragma once

#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <map>
#include <string>

namespace tl::lighting {

inline constexpr graph::ImageName kCompositeUnresolved{"composite.unresolved"};  // RGBA16F, this frame's jittered composite
// RGBA16F, the path's last resolved image: one per path (taa.history.<path>), so the Compare
// panel's sides, rendered in turn, never blend each other's images.
inline std::string taaHistoryName(const std::string& path) { return "taa.history." + path; }

// Whether this frame is anti-aliased temporally: the setting, for paths that rasterize a
// G-buffer (the reference path tracer jitters its own rays).
inline bool temporalAntialiasing(const RenderSettings& s, bool pathRasterizes) { return s.taa && pathRasterizes; }

class TaaPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);

 private:
  // Per path, the frame key of the last frame its TAA ran in: a history is used only by the
  // very next frame of that path (not after TAA was off or another path ran), and not across
  // a camera cut or a new scene.
  std::map<std::string, HistoryKeeper> keepers_;
};

}  // namespace tl::lighting
