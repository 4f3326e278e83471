#include "lighting/common/copy_pass.h"

#include "lighting/common/pass_builders.h"

namespace tl::lighting {

void addCopyPass(graph::RenderGraph& graph, std::string_view name, std::vector<ImageCopy> copies) {
  TransferPass pass{std::string(name)};
  for (const ImageCopy& c : copies) pass.copy(graph::ImageName{c.from}, graph::ImageName{c.to});
  pass.add(graph);
}

}  // namespace tl::lighting
