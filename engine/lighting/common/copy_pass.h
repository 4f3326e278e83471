// A transfer pass of copies alone (TransferPass's common case, pass_builders.h): how paths keep
// this frame's results as next frame's history, and views keep a copy to compare against.
#pragma once

#include "graph/graph.h"

#include <string>
#include <string_view>
#include <vector>

namespace tl::lighting {

struct ImageCopy {
  ImageCopy(graph::ImageName source, graph::ImageName destination) : from(source), to(destination) {}
  std::string from, to;
};

void addCopyPass(graph::RenderGraph& graph, std::string_view name, std::vector<ImageCopy> copies);

}  // namespace tl::lighting
