#include "lighting/lighting_path.h"

namespace tl::lighting {
namespace {

// Adds no passes: the composite's neutral inputs (AO = 1, the unoccluded sky) are exactly
// "direct sun + sky, no indirect light".
class DirectPath final : public LightingPath {
 public:
  std::string name() const override { return "direct"; }
  std::string description() const override { return "sun with shadows + unoccluded sky, no indirect light"; }
  PathCapabilities capabilities() const override { return {}; }
  LightingOutputs addPasses(graph::RenderGraph&, FrameInputs&) override { return {}; }
};

}  // namespace

std::unique_ptr<LightingPath> makeDirectPath() { return std::make_unique<DirectPath>(); }

}  // namespace tl::lighting
