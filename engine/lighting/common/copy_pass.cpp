#include "lighting/common/copy_pass.h"

#include "graph/executor.h"

namespace tl::lighting {

void addCopyPass(graph::RenderGraph& graph, std::string_view name, std::vector<ImageCopy> copies) {
  graph.addPass(
      name, graph::PassKind::Transfer,
      [&](graph::PassBuilder& b) {
        for (const auto& c : copies) {
          b.read(c.from, graph::Usage::TransferSrc);
          b.write(c.to, graph::Usage::TransferDst);
        }
      },
      [copies](graph::PassContext& ctx) {
        for (const auto& c : copies) gpu::copyImage(ctx.cmd, ctx.image(c.from), ctx.image(c.to));
      });
}

}  // namespace tl::lighting
