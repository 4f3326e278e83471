// Temporal anti-aliasing of the final image (shared/taa.h): the composite, rendered with a
// jittered projection, goes in as composite.unresolved; the resolved image comes out as
// composite.hdr, the name everything downstream (tonemap, captures, compare, the paths'
// screen feedback) already reads. Its history is the graph's persistent taa.history.
#pragma once

#include "gpu/pipeline.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

namespace tl::lighting {

inline constexpr const char* kCompositeUnresolved = "composite.unresolved";  // RGBA16F, this frame's jittered composite
inline constexpr const char* kTaaHistory = "taa.history";                    // RGBA16F, last frame's resolved image

// Whether this frame is anti-aliased temporally: the setting, for paths that rasterize a
// G-buffer (the reference path tracer jitters its own rays).
inline bool temporalAntialiasing(const RenderSettings& s, bool pathRasterizes) { return s.taa && pathRasterizes; }

class TaaPass {
 public:
  void add(graph::RenderGraph& graph, FrameInputs& in);

 private:
  gpu::Pipeline pipeline_;
  gpu::Sampler pointSampler_;
  gpu::Sampler linearSampler_;
};

}  // namespace tl::lighting
