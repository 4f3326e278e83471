// The `ao` plugin: the scene's ambient occlusion as a grey image (white = unoccluded, black
// sky). The AO is the rt path's ray-traced AO (RTAO: one ray per pixel within rtAoRadius,
// accumulated and filtered; the same image the rt path's composite multiplies the sky by), so
// what it shows is exactly what the rt path darkens; the path runs the rt path's passes and
// replaces its image by one pass.
#include "lighting/common/composite_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/lighting_path.h"

#include "shaders/ao_debug.h"

namespace tl::plugins {
namespace {

using namespace lighting;

constexpr graph::ImageName kAoGrey{"ao.grey"};

class AoDebugPath final : public LightingPath {
 public:
  std::string name() const override { return "ao"; }
  std::string description() const override {
    return "debug: the rt path's ray-traced AO as a grey image (white = unoccluded, black sky)";
  }
  PathCapabilities capabilities() const override {
    PathCapabilities c = source_->capabilities();
    c.halfResolution = false;  // its own settings are the rt path's
    c.debugView = true;        // AO, not radiance
    return c;
  }
  std::vector<std::pair<std::string, double>> figures() const override { return source_->figures(); }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    const LightingOutputs traced = source_->addPasses(graph, in);
    const uint32_t w = in.settings.width, h = in.settings.height;
    ComputePass(in.device, std::string(kAoGrey), "plugins/ao_debug/shaders/ao_grey.comp")
        .sampled(shared::kAoDebugSource, graph::ImageName{traced.ambientOcclusion})
        .sampled(shared::kAoDebugDepth, gbuffer::kDepth)
        .storageOut(shared::kAoDebugOutput, kAoGrey,
                    in.screenImage(kCompositeHdrFormat, "ambient occlusion as grey radiance"))
        .dispatch(w, h)
        .add(graph);
    LightingOutputs out;
    out.radiance = kAoGrey;
    return out;
  }

 private:
  std::unique_ptr<LightingPath> source_ = makeRtPath();
};

std::unique_ptr<LightingPath> makeAoDebugPath() { return std::make_unique<AoDebugPath>(); }
const LightingPathRegistrar registrar(makeAoDebugPath);

}  // namespace
}  // namespace tl::plugins
