// A history kept in graph resources, declared in one call: each resource persistent, and one
// decision for all of them from the frame key (frame_key.h) and from whether every one still
// holds last frame's contents. What a history's owner wrote by hand before, resource by
// resource: the validity checks, the keeper's advance, the persistent declarations.
//
//   const HistoryDecision d = keepHistory(graph, in, keeper_, kPolicy, name(),
//                                         {{kHistShY, shYDesc}, {kHistDepth, depthDesc}});
//   push.restart = d.action == HistoryAction::Restart;
#pragma once

#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/frame_key.h"

#include <string_view>
#include <vector>

namespace tl::lighting {

struct HistoryResource {
  std::string_view name;
  graph::ResourceDesc desc;
};

// Declares each resource persistent and advances `keeper` for the frame `in` renders as path
// `path`: a restart when any resource lost its contents (a resize, Session::resetHistory),
// else what `policy` says of the key's parts that changed, and of `restarts` (parts the owner
// judged to restart it: HistoryFound::restarts).
HistoryDecision keepHistory(graph::RenderGraph& graph, FrameInputs& in, HistoryKeeper& keeper, const HistoryPolicy& policy,
                            std::string_view path, const std::vector<HistoryResource>& resources, FrameParts restarts = 0);

}  // namespace tl::lighting
