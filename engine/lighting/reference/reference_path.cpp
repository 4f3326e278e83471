// The reference path: a progressive path tracer on the ray-tracing pipeline. It
// accumulates into a persistent sum while nothing that changes the image changes (camera,
// projection, light, scene, geometry, its settings: the frame key) and starts over when
// something does.
#include "graph/executor.h"
#include "lighting/common/decoders.h"
#include "lighting/lighting_path.h"
#include "lighting/common/emitter_table.h"
#include "lighting/common/environment_table.h"
#include "lighting/common/history.h"
#include "lighting/common/light_table.h"
#include "lighting/common/lights_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/scene_accel.h"
#include "shared/lights.h"
#include "lighting/reference/reference_path.h"
#include "scene/material_average.h"
#include "scene/scene.h"
#include "shared/brdf_lut.h"
#include "shared/reference.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <cstring>

namespace tl::lighting {
namespace {

inline constexpr graph::ImageName kRadiance{"reference.radiance"};
inline constexpr graph::ImageName kPilotMean{"reference.pilot.mean"};
inline constexpr graph::ImageName kPilotMoments{"reference.pilot.moments"};
inline constexpr graph::ImageName kAo{"reference.ao"};
inline constexpr graph::ImageName kIrradianceAccum{"reference.irradianceAccum"};
inline constexpr graph::ImageName kIrradiance{"reference.irradiance"};
inline constexpr graph::ImageName kDepthAccum{"reference.bouncesAccum"};
inline constexpr graph::ImageName kMoments{"reference.moments"};
inline constexpr graph::ImageName kSampleMean{"reference.sampleMean"};
inline constexpr graph::BufferName kNoiseTiles{"reference.noise.tiles"};

// Every part of the frame key changes the converged image except the per-instance hit
// albedo (the RT path's, not the materials the reference shades with): the sums start over.
constexpr HistoryPolicy kAccumulation{
    "reference.accumulation",
    parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection, FramePart::Sun, FramePart::Sky,
          FramePart::Scene, FramePart::Geometry, FramePart::Settings),
    0};

// The ray-tracing shaders of both pipelines, in their stages' order.
constexpr const char* kRaygen = "reference/trace.rgen";
constexpr const char* kIrradianceRaygen = "reference/irradiance.rgen";
constexpr const char* kDepthRaygen = "reference/bounces.rgen";
constexpr const char* kMisses[] = {"reference/trace.rmiss", "reference/shadow.rmiss"};
constexpr const char* kClosestHit = "reference/trace.rchit";
constexpr const char* kAnyHit = "reference/alpha.rahit";  // alpha MASK and BLEND: runs on non-opaque geometry only
// Shadow rays' hit group (shared/reference.h kRefShadowHitGroup): cut-outs and transmission.
constexpr const char* kShadowAnyHit = "reference/shadow.rahit";

// The three pipelines: the same paths, misses and hit shaders from three ray generations.
const RayShaders kTraceShaders{"reference.trace",
                               kRaygen,
                               {std::begin(kMisses), std::end(kMisses)},
                               {{kClosestHit, kAnyHit}, {"", kShadowAnyHit}}};
const RayShaders kIrradianceShaders{"reference.irradiance", kIrradianceRaygen, kTraceShaders.misses, kTraceShaders.hitGroups};
const RayShaders kDepthShaders{"reference.bounces", kDepthRaygen, kTraceShaders.misses, kTraceShaders.hitGroups};
// The benchmark's trivial kernel (bench --rays): the rt path's distance-only hit and miss shaders.
const RayShaders kRawShaders{"reference.rawRays", "reference/raw.rgen", {"rt/raw.rmiss"}, {{"rt/raw.rchit", ""}}};

class ReferencePath final : public LightingPath {
 public:
  std::string name() const override { return "reference"; }
  std::string description() const override {
    return "progressive path tracer (ground truth): same materials, sun, sky and emitters";
  }
  PathCapabilities capabilities() const override {
    return {.needsRayTracing = true,
            .isReference = true,
            .accumulates = true,
            .rasterizes = false,
            .readouts = {.image = std::string(kRadiance),
                         .ambientOcclusion = std::string(kAo),
                         .irradiance = std::string(kIrradiance),
                         .noise = std::string(kReferenceStdErr),
                         .noiseTotals = std::string(kReferenceNoise),
                         .byDepth = referenceBounceBuffers(),
                         .byLobe = referenceLobeBuffers(),
                         .shaders = referenceShaders()}};
  }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    // The scene's full structures, borrowed (SceneAccel: every triangle, deforming meshes
    // rebuilt exactly, the top level over every instance).
    structures_ = traceStructures(graph, in, AccelDetail::Full);
    prepareScene(in);
    const uint32_t w = in.settings.width, h = in.settings.height;
    const auto momentsDesc = in.screenImage(
        VK_FORMAT_R32G32B32A32_SFLOAT, "squared deviations of the samples from their mean, summed (rgb), samples (a)");
    const auto sampleMeanDesc =
        in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "mean of the pixel's samples (rgb), their mean AO (a)");
    const auto pilotMeanDesc = in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                              "adaptive sampling's pilot: mean of its samples (rgb), samples (a)");
    const auto pilotMomentsDesc = in.screenImage(
        VK_FORMAT_R32G32B32A32_SFLOAT, "adaptive sampling's pilot: squared deviations from its mean, summed (rgb)");
    const auto noiseDesc = graph::ResourceDesc::buffer(
        sizeof(shared::RefNoiseTotals), "the reference's noise over the image (shared/reference.h RefNoiseTotals); the "
                                        "next frame's trace allocates its samples by it");
    const HistoryDecision accumulation = keepHistory(graph, in, accumulation_, kAccumulation, name(),
                                                     {{kMoments, momentsDesc},
                                                      {kSampleMean, sampleMeanDesc},
                                                      {kPilotMean, pilotMeanDesc},
                                                      {kPilotMoments, pilotMomentsDesc},
                                                      {kReferenceNoise, noiseDesc}});
    if (accumulation.action == HistoryAction::Restart) samples_ = 0, irradianceSamples_ = 0;
    shared::RefPush push{};
    push.aoRadius = in.settings.rtAoRadius;  // resolved (render_settings.h resolveAutomatic)
    push.samplesPerFrame = std::max(1u, in.settings.referenceSamplesPerFrame);
    push.maxBounces = std::max(1u, in.settings.referenceBounces);
    push.emitterCount = in.settings.referenceEmitterSampling ? emitterCount_ : 0u;
    shared::RefPush tracePush = push;
    tracePush.adaptive = in.settings.referenceAdaptive;
    withPathInputs(RayTracingPass(in.device, "reference.trace", kTraceShaders), in)
        .storageInOut(shared::kRefBindingMoments, kMoments)
        .storageInOut(shared::kRefBindingSampleMean, kSampleMean)
        .storageInOut(shared::kRefBindingPilotMean, kPilotMean)
        .storageInOut(shared::kRefBindingPilotMoments, kPilotMoments)
        .bufferIn(shared::kRefBindingLastNoise, kReferenceNoise)
        .storageOut(shared::kRefBindingAllocation, kReferenceAllocation,
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                   "where this frame's samples went: the pixel's samples (x) and the "
                                   "first one's number (y); the standard deviation the next frame "
                                   "allocates by (z)"))
        .storageOut(shared::kRefBindingStdErr, kReferenceStdErr,
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                   "standard error of reference.radiance per channel (rgb: how far each "
                                   "pixel's estimate is expected to be from the converged one), the "
                                   "pixel's samples (a)"))
        .storageOut(
            shared::kRefBindingAo, kAo,
            in.screenImage(VK_FORMAT_R32_SFLOAT, "ambient occlusion at the AO radius (cosine-weighted), ground truth")
                .decodedAs("ao"))
        .storageOut(shared::kRefBindingRadiance, kRadiance,
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "path-traced radiance"))
        .push(tracePush,
              [this](graph::PassContext& ctx, shared::RefPush& p) {
                // History can vanish under us (resize, reset): then the sum starts over.
                if (!ctx.historyValid(kMoments) || !ctx.historyValid(kSampleMean) || !ctx.historyValid(kPilotMean) ||
                    !ctx.historyValid(kPilotMoments) || !ctx.historyValid(kReferenceNoise))
                  samples_ = 0;
                p.samplesSoFar = samples_;
                p.seed = 0;
                samples_ += p.samplesPerFrame;
              })
        .trace(w, h)
        .add(graph);
    addNoisePasses(graph, in);
    addIrradiancePass(graph, in, push);
    addDepthSplitPass(graph, in, push);
    if (in.settings.referenceRawRayProbe) addRawRayPass(graph, in, push);
    LightingOutputs out;
    out.radiance = kRadiance;
    return out;
  }

  uint32_t samples() const { return samples_; }

  // bench --rays: the reference's paths per second against the raw kernel's rays per second on
  // its top level, in the same frames.
  bool enableRayProbe(RenderSettings& settings) const override {
    settings.referenceRawRayProbe = true;
    return true;
  }
  std::vector<std::string> rayProbeReadbacks() const override { return {std::string(kReferenceRawRays)}; }
  std::vector<std::pair<std::string, double>> rayFigures(const RayProbeFrame& frame) const override {
    double rawRays = 0.0;
    for (float c : frame.readback(kReferenceRawRays).texels()) rawRays += c;
    const double pixels = double(frame.settings.width) * frame.settings.height;
    const double paths = pixels * frame.settings.referenceSamplesPerFrame;
    const double rawMs = frame.medianMs("reference.rawRays"), traceMs = frame.medianMs("reference.trace");
    const double rawRate = RayProbeFrame::perSecond(rawRays, rawMs);
    const double pathRate = RayProbeFrame::perSecond(paths, traceMs);
    return {{"paths", paths},  // this frame's: samples per frame a pixel (adaptive sampling spreads them)
            {"traceMs", traceMs},
            {"pathsPerSecond", pathRate},
            {"rawRays", rawRays},
            {"rawRaysPerPath", paths > 0.0 ? rawRays / paths : 0.0},
            {"rawKernelMs", rawMs},
            {"rawRaysPerSecond", rawRate},
            // What one path costs, in the trivial kernel's rays: the raw rate over the path rate.
            {"rawRaysPerPathTime", pathRate > 0.0 ? rawRate / pathRate : 0.0}};
  }

  std::vector<std::pair<std::string, double>> figures() const override {
    return {{"reference.samples", double(samples_)},
            {"reference.irradianceSamples", double(irradianceSamples_)},
            {"reference.bounceSamples", double(depthSamples_)}};
  }

 private:
  // The image's noise (shared/reference.h RefNoiseTotals) summed on the GPU in two steps and
  // read back every frame: 32 bytes, so the session knows the relative standard error of every
  // frame it finishes (Session::referenceNoise) without reading the images. It persists: the
  // next frame's trace allocates its samples by its mean sigma.
  void addNoisePasses(graph::RenderGraph& graph, FrameInputs& in) {
    const uint32_t w = in.settings.width, h = in.settings.height;
    shared::RefNoisePush push{};
    push.width = w, push.height = h;
    push.tiles = ((w + shared::kRefNoiseTile - 1) / shared::kRefNoiseTile) * ((h + shared::kRefNoiseTile - 1) / shared::kRefNoiseTile);
    ComputePass(in.device, "reference.noise.tiles", "reference/noise_tiles.comp")
        .storageIn(shared::kRefNoiseBindingRadiance, kRadiance)
        .storageIn(shared::kRefNoiseBindingStdErr, kReferenceStdErr)
        .storageIn(shared::kRefNoiseBindingAllocation, kReferenceAllocation)
        .bufferOut(shared::kRefNoiseBindingTiles, kNoiseTiles,
                   graph::ResourceDesc::buffer(push.tiles * sizeof(shared::RefNoiseTotals),
                                               "the reference's noise summed per 16 x 16 tile"))
        .push(push)
        .dispatch(w, h, 1, shared::kRefNoiseTile, shared::kRefNoiseTile)
        .add(graph);
    ComputePass(in.device, "reference.noise", "reference/noise_sum.comp")
        .bufferIn(shared::kRefNoiseBindingTiles, kNoiseTiles)
        .bufferOut(shared::kRefNoiseBindingTotals, kReferenceNoise)
        .push(push)
        .dispatch(256, 1, 1, 256, 1, 1)
        .add(graph);
    graph.markOutput(kReferenceNoise);
    graph.requestReadback(kReferenceNoise);
  }

  // The benchmark's trivial kernel (reference/raw.rgen) on the same top level, samplesPerFrame
  // short paths of rays a pixel: the device's raw ray rate, which `bench --rays` holds the
  // reference's paths per second against (rayFigures).
  void addRawRayPass(graph::RenderGraph& graph, FrameInputs& in, shared::RefPush push) {
    const uint32_t w = in.settings.width, h = in.settings.height;
    push.samplesSoFar = samples_;
    RayTracingPass(in.device, "reference.rawRays", kRawShaders)
        .uniform(shared::kRefBindingFrame, kFrameConstants)
        .accelerationStructure(shared::kRefBindingTlas, structures_.tlas, structures_.names)
        .storageOut(shared::kRefBindingRawRays, kReferenceRawRays,
                    in.screenImage(VK_FORMAT_R32_SFLOAT, "benchmark: rays the trivial kernel traced per pixel"))
        .push(push)
        .trace(w, h)
        .add(graph);
    graph.markOutput(kReferenceRawRays);
  }

  // The diffuse irradiance at the primary hit (what composite.irradiance holds for the
  // real-time paths), its own progressive sum. It costs a second path per sample, so it runs
  // only in frames that read reference.irradiance (compare's per-stage error, the inspector).
  void addIrradiancePass(graph::RenderGraph& graph, FrameInputs& in, shared::RefPush push) {
    const uint32_t w = in.settings.width, h = in.settings.height;
    graph.declareOnDemandHistory(
        kIrradianceAccum,
        in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, "sum of irradiance samples (rgb) and their count (a)"));
    withPathInputs(RayTracingPass(in.device, "reference.irradiance", kIrradianceShaders), in)
        .storageInOut(shared::kRefBindingIrradianceAccum, kIrradianceAccum)
        .storageOut(shared::kRefBindingIrradiance, kIrradiance,
                    in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                                   "diffuse irradiance at the primary hit: sky + bounce light, no sun "
                                   "(0: sky), ground truth"))
        .push(push,
              [this](graph::PassContext& ctx, shared::RefPush& p) {
                if (!ctx.historyValid(kIrradianceAccum)) irradianceSamples_ = 0;
                p.samplesSoFar = irradianceSamples_;
                p.seed = 1;  // independent of the radiance samples
                irradianceSamples_ += p.samplesPerFrame;
              })
        .trace(w, h)
        .add(graph);
  }

  // The radiance split by path depth (referenceBounceBuffers()) and by the first surface's lobe
  // (referenceLobeBuffers()), each part its own progressive sum. It traces the trace pass's paths
  // a second time (the counts and sample numbers the trace wrote to reference.allocation this
  // frame), so it runs only in frames that read one of its buffers (compare's per-bounce and
  // per-lobe figures, the inspector); requested in every frame since the reference's sum started,
  // its four depth images sum to reference.radiance, and its two lobes to the radiance less what
  // the camera sees directly. Its sums restart with the reference's (a frame whose trace starts over).
  void addDepthSplitPass(graph::RenderGraph& graph, FrameInputs& in, shared::RefPush push) {
    const uint32_t w = in.settings.width, h = in.settings.height;
    graph.declareOnDemandHistory(
        kDepthAccum, graph::ResourceDesc::image2D(
                         VK_FORMAT_R32G32B32A32_SFLOAT, w, h * (shared::kRefDepthGroups + shared::kRefLobes),
                         "sums of the radiance by path depth, then by the first surface's lobe (rgb) and "
                         "their count (a), the four groups and two lobes stacked vertically"));
    const auto names = referenceBounceBuffers();
    static const char* kWhat[] = {"emission and direct light (paths of 0 or 1 scattering events)",
                                  "the first bounce (2 scattering events)", "the second bounce (3 scattering events)",
                                  "the third bounce and more (4 or more scattering events)"};
    const uint32_t base = samples_;  // the trace pass's samples before this frame: the same paths
    RayTracingPass pass = withPathInputs(RayTracingPass(in.device, "reference.bounces", kDepthShaders), in);
    pass.storageInOut(shared::kRefBindingDepthAccum, kDepthAccum);
    pass.storageIn(shared::kRefBindingAllocation, kReferenceAllocation);
    for (uint32_t g = 0; g < shared::kRefDepthGroups; ++g)
      pass.storageOut(shared::kRefBindingDepth0 + g, graph::ImageName{names[g]},
                      in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT, fmt::format("path-traced radiance of {}", kWhat[g]))
                          .decodedAs(fmt::format("{} whole={}", kDepthShareDecoder, kRadiance.name())));
    const auto lobes = referenceLobeBuffers();
    static const char* kLobe[] = {"the diffuse layer", "the specular lobes (highlights and reflections)"};
    for (uint32_t l = 0; l < shared::kRefLobes; ++l)
      pass.storageOut(
          shared::kRefBindingLobe0 + l, graph::ImageName{lobes[l]},
          in.screenImage(VK_FORMAT_R32G32B32A32_SFLOAT,
                         fmt::format("path-traced radiance the first surface reflects through {}", kLobe[l]))
              .decodedAs(fmt::format("{} whole={}", kDepthShareDecoder, kRadiance.name())));
    pass.push(push,
              [this, base](graph::PassContext& ctx, shared::RefPush& p) {
                const bool traceRestarted = base == 0 || !ctx.historyValid(kSampleMean);  // as the trace pass decides
                if (!ctx.historyValid(kDepthAccum) || traceRestarted) depthSamples_ = 0;
                p.samplesSoFar = depthSamples_;
                p.seed = 0;  // the trace pass's seed
                depthSamples_ += p.samplesPerFrame;
              })
        .trace(w, h)
        .add(graph);
  }

  // The per-instance geometry table and the emitters, once per scene (the pipelines are the
  // device's, RayTracingPass: built once, not with each scene, as on lavapipe each takes tens of
  // seconds to compile; and again only if the scene table's layout changes).
  void prepareScene(FrameInputs& in) {
    if (sceneId_ == in.scene.id()) return;
    in.device.waitIdle();
    sceneId_ = in.scene.id();
    const auto& ranges = in.scene.meshRanges();
    // The emitters (lighting/common/emitter_table.h): every triangle of each instance whose
    // material emits, drawn by its power from the material's average emission.
    std::vector<glm::vec3> instanceEmission;
    for (const auto& instance : in.sceneData.instances)
      instanceEmission.push_back(scene::materialAverageEmission(
          in.sceneData, in.sceneData.materials[in.sceneData.meshes[instance.mesh].material]));
    const EmitterTable emitters = buildEmitterTable(in.sceneData, instanceEmission);
    emitterCount_ = uint32_t(emitters.entries.size());
    std::vector<shared::Emitter> entries = emitters.entries;
    if (entries.empty()) entries.emplace_back();  // a binding needs a buffer
    emitters_ = gpu::Buffer(in.device, entries.size() * sizeof(shared::Emitter), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            gpu::MemoryUsage::Upload, "reference.emitters");
    emitters_.write(entries.data(), entries.size() * sizeof(shared::Emitter));
    std::vector<shared::RefInstanceGeometry> table(std::max<size_t>(1, in.scene.instanceCount()));
    for (size_t i = 0; i < in.scene.instanceCount(); ++i) {
      const auto& r = ranges[in.scene.instanceMesh(i)];
      table[i] = {r.firstIndex, r.vertexOffset, r.material, i < emitters.firstOfInstance.size() ? emitters.firstOfInstance[i] : 0u};
    }
    geometry_ = gpu::Buffer(in.device, table.size() * sizeof(table[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            gpu::MemoryUsage::Upload, "reference.instanceGeometry");
    geometry_.write(table.data(), table.size() * sizeof(table[0]));
  }

  // What every path-tracing pass (trace, irradiance, bounces) binds: the frame, the structures,
  // the hits' geometry, the BRDF tables, the light and environment tables where the scene has
  // them (path.glsl reads them only for frame.lightCount > 0 and with the environment flag),
  // and the scene table (set 1: the materials and textures the hits shade with).
  RayTracingPass withPathInputs(RayTracingPass pass, const FrameInputs& in) const {
    pass.uniform(shared::kRefBindingFrame, kFrameConstants)
        .accelerationStructure(shared::kRefBindingTlas, structures_.tlas, structures_.names)
        .constantBuffer(shared::kRefBindingGeometry, geometry_.handle())
        .bufferIn(shared::kRefBindingVertices, kSceneVertices)
        .bufferIn(shared::kRefBindingIndices, kSceneIndices)
        .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
        .optionalBufferIn(shared::kBindingLights, kLightTable, in.constants.lightCount > 0)
        .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, hasEnvironmentMap(in))
        .constantBuffer(shared::kRefBindingEmitters, emitters_.handle())
        .reads(kSceneInstances, graph::Usage::StorageRead)
        .reads(kSceneMaterials, graph::Usage::StorageRead)
        .sceneTable(in.scene.table());
    return pass;
  }

  uint64_t sceneId_ = 0;
  TraceStructures structures_;  // this frame's, borrowed from the SceneAccel
  gpu::Buffer geometry_;
  gpu::Buffer emitters_;  // shared::Emitter per emissive triangle (at least one entry; emitterCount_ valid)
  uint32_t emitterCount_ = 0;
  HistoryKeeper accumulation_;
  uint32_t samples_ = 0;
  uint32_t irradianceSamples_ = 0;
  uint32_t depthSamples_ = 0;
};

}  // namespace

const std::vector<std::string>& referenceBounceBuffers() {
  static const std::vector<std::string> names = {"reference.bounce0", "reference.bounce1", "reference.bounce2",
                                                 "reference.bounce3plus"};
  return names;
}

const std::vector<std::string>& referenceLobeBuffers() {
  static const std::vector<std::string> names = {"reference.diffuse", "reference.specular"};
  return names;
}

std::unique_ptr<LightingPath> makeReferencePath() { return std::make_unique<ReferencePath>(); }

std::vector<std::string> referenceShaders() {
  std::vector<std::string> all{kRaygen, kIrradianceRaygen, kDepthRaygen};
  all.insert(all.end(), std::begin(kMisses), std::end(kMisses));
  all.push_back(kClosestHit);
  all.push_back(kAnyHit);
  all.push_back(kShadowAnyHit);
  return all;
}

}  // namespace tl::lighting
