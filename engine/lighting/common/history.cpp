#include "lighting/common/history.h"

#include <algorithm>

namespace tl::lighting {

HistoryDecision keepHistory(graph::RenderGraph& graph, FrameInputs& in, HistoryKeeper& keeper, const HistoryPolicy& policy,
                            std::string_view path, const std::vector<HistoryResource>& resources, FrameParts restarts) {
  // Validity is asked before the declarations: a resource declared this frame with another
  // description (a resize) is new, whatever it held.
  const bool stored = std::all_of(resources.begin(), resources.end(),
                                  [&](const HistoryResource& r) { return in.historyValid(r.name, r.desc); });
  HistoryDecision decision = keeper.advance(policy, in.key, path, in.historyLog, {stored, restarts});
  for (const HistoryResource& r : resources) graph.declarePersistent(r.name, r.desc);
  return decision;
}

}  // namespace tl::lighting
