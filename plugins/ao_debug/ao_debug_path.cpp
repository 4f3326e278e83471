// The `ao` plugin: the scene's ambient occlusion as a grey image (white = unoccluded, black
// sky), by the definition the rt path's AO and the reference's share (cosine rays from the
// surface, occluded by a hit within rtAoRadius). It traces its own rays (shaders/ao_trace.comp)
// against the scene's simplified structures, which every real-time tracer borrows
// (lighting/common/scene_accel.h): its GPU time is one pass and the culled top level's build,
// none of the rt path's passes.
#include "lighting/common/composite_pass.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/history.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/scene_accel.h"
#include "lighting/lighting_path.h"

#include "shaders/ao_debug.h"

#include <algorithm>

namespace tl::plugins {
namespace {

using namespace lighting;

// Its settings, in the schema beside the engine's (JSON, `--set`, the editor's ao group).
const PluginSetting<uint32_t> kRays{"aoDebugRays", 2, 1, 64, "rays", "ao", "", kSettingPlain,
                                    "AO rays per pixel and frame (cosine-distributed, as long as rtAoRadius)"};
const PluginSetting<uint32_t> kMaxFrames{"aoDebugMaxFrames", 64, 1, 1024, "frames", "ao", "", kSettingPlain,
                                         "accumulation window while the view holds still"};
// The engine's setting that changes what its running mean estimates: the radius it borrows.
const HistoryInputsRegistrar kHistoryInputs{"ao", {"rtAoRadius"}};

constexpr graph::ImageName kHistory{"ao.history"};
constexpr graph::ImageName kAoGrey{"ao.grey"};

// What the running mean estimates changes with the view, the occluders (the scene, its
// geometry) and the settings above: any of these starts it over.
constexpr HistoryPolicy kAccumulation{
    "ao.accumulation",
    parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection, FramePart::Scene,
          FramePart::Geometry, FramePart::Settings),
    0};

class AoDebugPath final : public LightingPath {
 public:
  std::string name() const override { return "ao"; }
  std::string description() const override {
    return "debug: ray-traced AO within rtAoRadius as a grey image (white = unoccluded, black sky)";
  }
  PathCapabilities capabilities() const override {
    return {.needsRayTracing = true, .accumulates = true, .debugView = true};  // AO, not radiance
  }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    const TraceStructures& traced = traceStructures(graph, in, AccelDetail::Simplified);
    const RenderSettings& s = in.settings;

    const bool restart =
        keepHistory(graph, in, history_, kAccumulation, name(),
                    {{kHistory, in.screenImage(VK_FORMAT_R32_SFLOAT, "mean AO visibility, last frame")}})
            .action == HistoryAction::Restart;
    frames_ = restart ? 1 : std::min(frames_ + 1, kMaxFrames.of(s));

    shared::AoDebugPush push{};
    push.rays = kRays.of(s);  // at least 1: the schema's range
    push.frames = frames_;
    push.aoRadius = s.rtAoRadius;  // in.settings has automatic values resolved
    ComputePass(in.device, std::string(kAoGrey), "plugins/ao_debug/shaders/ao_trace.comp")
        .uniform(shared::kBindingFrame, kFrameConstants)
        .sampled(shared::kAoDebugNormal, gbuffer::kNormal)
        .sampled(shared::kAoDebugDepth, gbuffer::kDepth)
        .accelerationStructure(shared::kAoDebugTlas, traced.tlas, traced.names)
        .storageInOut(shared::kAoDebugHistory, kHistory)
        .storageOut(shared::kAoDebugOutput, kAoGrey,
                    in.screenImage(kCompositeHdrFormat, "ambient occlusion as grey radiance"))
        .push(push)
        .dispatch(s.width, s.height)
        .add(graph);

    LightingOutputs out;
    out.radiance = kAoGrey;
    return out;
  }

 private:
  HistoryKeeper history_;
  uint32_t frames_ = 0;
};

std::unique_ptr<LightingPath> makeAoDebugPath() { return std::make_unique<AoDebugPath>(); }
const LightingPathRegistrar registrar(makeAoDebugPath);

}  // namespace
}  // namespace tl::plugins
