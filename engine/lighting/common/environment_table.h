// The environment map's table on the GPU (shaders/shared/environment.h): imported into a
// frame's graph under kEnvironmentTable only when the lighting has a map; the reference path
// samples it. Frames without a map have no table and no pass reads one.
#pragma once

#include "graph/executor.h"
#include "lighting/common/frame_inputs.h"
#include "shared/frame.h"

namespace tl::lighting {

inline constexpr graph::BufferName kEnvironmentTable{"environment.table"};

inline bool hasEnvironmentMap(const FrameInputs& in) { return (in.constants.flags & shared::kFrameFlagEnvironment) != 0u; }

// What a pass that may sample the map binds at kBindingEnvironment: the table, or in frames
// without a map `standIn` (any buffer the pass binds anyway), which its shaders never read.
// Such a pass declares b.read(kEnvironmentTable) only when hasEnvironmentMap(in).
inline VkBuffer environmentTableOrStandIn(graph::PassContext& ctx, const FrameInputs& in, VkBuffer standIn) {
  return hasEnvironmentMap(in) ? ctx.buffer(kEnvironmentTable).handle() : standIn;
}

}  // namespace tl::lighting
