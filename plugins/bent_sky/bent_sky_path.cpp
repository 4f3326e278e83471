// The `bentsky` plugin: bent-normal sky occlusion (shaders/bent_sky.comp). Each pixel sees the
// sky through the rays that escape the scene: its irradiance is the visibility times the sky's
// irradiance along their mean direction, accumulated while the view holds still. Light does
// not bounce: set against rt (one bounce and more) and the reference, it shows what the bounce
// light is worth in a scene, at the price of sky visibility alone. It traces the scene's
// simplified structures (lighting/common/scene_accel.h), which every real-time tracer borrows:
// its GPU time is its own pass and the culled top level's build, not the rt path's passes.
#include "lighting/common/frame_inputs.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/history.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/scene_accel.h"
#include "lighting/lighting_path.h"

#include "shaders/bent_sky.h"

#include <algorithm>

namespace tl::plugins {
namespace {

using namespace lighting;

// Its settings, in the schema beside the engine's (JSON, `--set`, the editor's bentsky group).
const PluginSetting<uint32_t> kRays{"bentSkyRays", 4, 1, 64, "rays", "bentsky", "bentsky", kSettingPlain,
                                    "sky-visibility rays per pixel and frame (cosine-distributed, as long as rtRayLength)"};
const PluginSetting<uint32_t> kMaxFrames{"bentSkyMaxFrames", 32, 1, 1024, "frames", "bentsky", "", kSettingPlain,
                                         "accumulation window while the view holds still"};
// The engine's settings that change what its running mean estimates: the materials (the sun's
// shading), the light shadow maps it shades with and the length of its rays.
const HistoryInputsRegistrar kHistoryInputs{"bentsky", {"materials", "lightShadowMapSize", "lightShadowMaxLights", "rtRayLength"}};

constexpr graph::ImageName kHistory{"bentsky.history"};
constexpr graph::ImageName kShY{"bentsky.shY"};
constexpr graph::ImageName kCoCg{"bentsky.coCg"};
constexpr graph::ImageName kAo{"bentsky.ao"};

// What the running mean estimates changes with the view, the sun's shadow casters (the
// scene, its geometry) and its own settings: any of these starts it over.
constexpr HistoryPolicy kAccumulation{
    "bentsky.accumulation",
    parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection, FramePart::Scene,
          FramePart::Geometry, FramePart::Settings),
    0};

class BentSkyPath final : public LightingPath {
 public:
  std::string name() const override { return "bentsky"; }
  std::string description() const override {
    return "bent-normal sky occlusion: ray-traced sky visibility and bent normal, no bounce light";
  }
  PathCapabilities capabilities() const override { return {.needsRayTracing = true, .accumulates = true}; }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    const TraceStructures& traced = traceStructures(graph, in, AccelDetail::Simplified);
    const RenderSettings& s = in.settings;
    const uint32_t w = s.width, h = s.height;

    const auto historyDesc =
        in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "mean escaping direction (xyz) and visibility (w), last frame");
    const bool restart =
        keepHistory(graph, in, history_, kAccumulation, name(), {{kHistory, historyDesc}}).action == HistoryAction::Restart;
    frames_ = restart ? 1 : std::min(frames_ + 1, kMaxFrames.of(s));

    shared::BentSkyPush push{};
    push.rays = kRays.of(s);  // at least 1: the schema's range
    push.frames = frames_;
    push.rayLength = s.rtRayLength;  // in.settings has automatic values resolved
    ComputePass(in.device, "bentsky.trace", "plugins/bent_sky/shaders/bent_sky.comp")
        .uniform(shared::kBindingFrame, kFrameConstants)
        .sampled(shared::kBentSkyNormal, lighting::gbuffer::kNormal)
        .sampled(shared::kBentSkyDepth, gbuffer::kDepth)
        .accelerationStructure(shared::kBentSkyTlas, traced.tlas, traced.names)
        .storageInOut(shared::kBentSkyHistory, kHistory)
        .storageOut(shared::kBentSkyShY, kShY,
                    in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT, "sky irradiance, L1 SH of luma (L0 only)"))
        .storageOut(shared::kBentSkyCoCg, kCoCg, in.screenImage(VK_FORMAT_R16G16_SFLOAT, "sky irradiance, chroma"))
        .storageOut(shared::kBentSkyAo, kAo, in.screenImage(VK_FORMAT_R16_SFLOAT, "sky visibility (cosine-weighted)"))
        .push(push)
        .dispatch(w, h)
        .add(graph);

    LightingOutputs out;
    out.ambientOcclusion = kAo;
    out.diffuseShY = kShY;
    out.diffuseCoCg = kCoCg;
    out.openSkyDirectionality = 0.0f;  // the SH carries no direction (bent_sky.comp)
    out.shadowStructures = traced.names;  // the light table's shadow rays too
    out.shadowTlasHandle = traced.tlas;
    return out;
  }

 private:
  HistoryKeeper history_;
  uint32_t frames_ = 0;
};

std::unique_ptr<LightingPath> makeBentSkyPath() { return std::make_unique<BentSkyPath>(); }
const LightingPathRegistrar registrar(makeBentSkyPath);

}  // namespace
}  // namespace tl::plugins
