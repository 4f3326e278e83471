// A transfer pass that copies images into others of the same size, declared to the graph:
// how paths keep this frame's results as next frame's history, and views keep a copy to compare against.
#pragma once

#include "graph/graph.h"

#include <string>
#include <utility>
#include <vector>

namespace tl::lighting {

struct ImageCopy {
  std::string from, to;
};

void addCopyPass(graph::RenderGraph& graph, std::string_view name, std::vector<ImageCopy> copies);

}  // namespace tl::lighting
