// The `ao` plugin: the scene's ambient occlusion as a grey image (white = unoccluded, black
// sky). The AO is the rt path's ray-traced AO (RTAO: one ray per pixel within rtAoRadius,
// accumulated and filtered; the same image the rt path's composite multiplies the sky by), so
// what it shows is exactly what the rt path darkens; the path runs the rt path's passes and
// replaces its image by one pass.
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/lighting_path.h"

#include "shaders/ao_debug.h"

namespace tl::plugins {
namespace {

using namespace lighting;

constexpr const char* kAoGrey = "ao.grey";

class AoDebugPath final : public LightingPath {
 public:
  std::string name() const override { return "ao"; }
  std::string description() const override {
    return "debug: the rt path's ray-traced AO as a grey image (white = unoccluded, black sky)";
  }
  PathCapabilities capabilities() const override {
    PathCapabilities c = source_->capabilities();
    c.halfResolution = false;  // its own settings are the rt path's
    return c;
  }
  std::vector<std::pair<std::string, double>> figures() const override { return source_->figures(); }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    const LightingOutputs traced = source_->addPasses(graph, in);
    if (!pipeline_) {
      gpu::ComputePipelineDesc d;
      d.name = kAoGrey;
      d.shader = "plugins/ao_debug/shaders/ao_grey.comp";
      d.layout.bindings = {{shared::kAoDebugSource, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kAoDebugDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                           {shared::kAoDebugOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
      pipeline_ = gpu::createComputePipeline(in.device, d);
      sampler_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "ao.point");
    }
    const uint32_t w = in.settings.width, h = in.settings.height;
    const std::string ao = traced.ambientOcclusion;
    graph.addPass(
        kAoGrey, graph::PassKind::Compute,
        [&](graph::PassBuilder& b) {
          b.read(ao, graph::Usage::Sampled);
          b.read(kGbufferDepth, graph::Usage::Sampled);
          b.create(kAoGrey, graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h, "ambient occlusion as grey radiance"),
                   graph::Usage::StorageWrite);
        },
        [this, ao, w, h](graph::PassContext& ctx) {
          const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
          ctx.bind(pipeline_);
          ctx.descriptors()
              .sampledImage(shared::kAoDebugSource, ctx.image(ao).view(), sampler_.handle(), ro)
              .sampledImage(shared::kAoDebugDepth, ctx.image(kGbufferDepth).view(), sampler_.handle(), ro)
              .storageImage(shared::kAoDebugOutput, ctx.image(kAoGrey).view());
          ctx.dispatch(w, h);
        });
    LightingOutputs out;
    out.radiance = kAoGrey;
    return out;
  }

 private:
  std::unique_ptr<LightingPath> source_ = makeRtPath();
  gpu::Pipeline pipeline_;
  gpu::Sampler sampler_;
};

std::unique_ptr<LightingPath> makeAoDebugPath() { return std::make_unique<AoDebugPath>(); }
const LightingPathRegistrar registrar(makeAoDebugPath);

}  // namespace
}  // namespace tl::plugins
