// The ray-traced lighting path ("RTX ON"), after Metro Exodus (GDC 2019): top level rebuilt
// from culled instances, screen-space pre-trace, real rays only where it failed, deferred
// lighting of the hit points into L1 SH of luma + CoCg, RTAO from the same hit distances,
// temporal accumulation, and a small AO filter. Every intermediate is a named resource.
#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/decoders.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/history.h"
#include "lighting/common/light_table.h"
#include "lighting/common/lights_pass.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/scene_accel.h"
#include "lighting/lighting_path.h"
#include "lighting/rt/blue_noise.h"
#include "lighting/rt/radiance_cache.h"
#include "lighting/common/environment_table.h"
#include "lighting/rt/rt_path.h"
#include "lighting/rt/rt_scene.h"
#include "shared/brdf_lut.h"
#include "shared/rt_specular.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <cstring>

namespace tl::lighting {
namespace {

using graph::Usage;
using shared::RtPush;

// Alpha MASK for every ray that meets the scene: invoked only on geometry built without
// VK_GEOMETRY_OPAQUE_BIT (meshes whose material cuts itself out), so opaque scenes never pay.
constexpr const char* kAnyHit = "rt/alpha.rahit";

// The ray-tracing pipelines' shaders. Those that trace the scene have the any-hit shader, which
// reads the materials through the scene table (set 1). hit_lighting.glsl: the shadow miss is 0.
const RayShaders kTraceShaders{"rt.trace", "rt/trace.rgen", {"rt/trace.rmiss"}, {{"rt/trace.rchit", kAnyHit}}};
// Shadow rays skip closest hits; cut-outs still let them through.
const RayShaders kLightingShaders{"rt.lighting", "rt/lighting.rgen", {"rt/shadow.rmiss"}, {{"", kAnyHit}}};
const RayShaders kDisocclusionShaders{"rt.disocclusion", "rt/disocclusion.rgen",
                                      {"rt/shadow.rmiss", "rt/disocclusion.rmiss"}, {{"rt/disocclusion.rchit", kAnyHit}}};
// The whole hit in the payload, as the disocclusion rays have it.
const RayShaders kCacheUpdateShaders{"rt.cache.update", "rt/cache_update.rgen",
                                     {"rt/shadow.rmiss", "rt/disocclusion.rmiss"}, {{"rt/disocclusion.rchit", kAnyHit}}};
// Reflections: the whole hit in the payload, as the disocclusion rays have it.
const RayShaders kSpecularShaders{"rt.specular", "rt/specular.rgen", {"rt/shadow.rmiss", "rt/disocclusion.rmiss"},
                                  {{"rt/disocclusion.rchit", kAnyHit}}};
const RayShaders kRawShaders{"rt.rawRays", "rt/raw.rgen", {"rt/raw.rmiss"}, {{"rt/raw.rchit", ""}}};

// The temporal accumulation (SH, chroma, AO, depth, luma moment) and last frame's radiance
// that hits on screen reuse. Camera motion is reprojected, except a cut; a new scene or a
// setting its samples depend on restarts it; a change of the light the rays gather (sun,
// sky, hit albedo) clips it to this frame's samples (luminance rejection, when on).
constexpr FrameParts kTemporalRestarts = parts(FramePart::Scene, FramePart::Settings, FramePart::CameraCut);
constexpr FrameParts kTemporalRejects = parts(FramePart::Sun, FramePart::Sky, FramePart::Albedo);

// The spatial filters' Poisson disk turns by the golden angle each frame (radians), so
// successive frames' taps never line up.
float goldenAngleRotation(uint32_t frameIndex) { return float(frameIndex % 1024u) * 2.3999632f; }

class RtPath final : public LightingPath {
 public:
  std::string name() const override { return "rt"; }
  std::string description() const override {
    return "ray-traced GI + AO (Metro Exodus): pre-trace, 1 ray/pixel, SH irradiance, temporal accumulation";
  }
  PathCapabilities capabilities() const override {
    return {.needsRayTracing = true, .accumulates = true, .halfResolution = true};
  }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    // The scene's simplified structures, borrowed (their build, refits and culled top level
    // are SceneAccel's passes, added once per frame whoever asks first).
    structures_ = traceStructures(graph, in, AccelDetail::Simplified);
    accelStats_ = in.accel->stats(AccelDetail::Simplified);
    prepare(in);
    const RenderSettings& s = in.settings;
    // in.settings has every automatic value resolved (render_settings.h resolveAutomatic).
    const float scale = std::max(in.constants.sceneScale, 1e-30f);
    params_ = RtResolvedParams{};
    params_.aoRadius = s.rtAoRadius;
    params_.rayLength = s.rtRayLength;
    params_.blendDistance = s.rtBlendDistance;
    params_.tMin = 1.5f * accelStats_.maxDeviation + 1e-5f * scale;

    RtPush push{};
    push.tMin = params_.tMin;
    push.tMax = params_.rayLength;
    push.aoRadius = params_.aoRadius;
    push.pretrace = s.rtPretrace ? 1u : 0u;
    push.rayPattern = rtRayPattern(s);
    push.pretraceSteps = s.rtPretraceSteps;
    push.pretraceLength = s.rtPretracePixels;
    push.thickness = s.rtThickness;
    push.maxAccumFrames = s.rtMaxAccumFrames;
    push.fireflyClamp = std::max(s.rtFireflyClamp, 0.0f);
    // Metro's denoiser radii are 6 m and 3 m in its world; here a sixth of the scene.
    const float denoiseRadius = s.rtDenoiseRadius;
    push.hitDistanceCap = denoiseRadius;
    const uint32_t w = s.width, h = s.height;
    auto image = [&](VkFormat f, const char* what) { return in.screenImage(f, what); };
    // Luminance rejection is triggered by a change of the light (see shared/rt.h).
    const HistoryPolicy temporal{"rt.temporal", kTemporalRestarts, s.rtLumaRejection ? kTemporalRejects : 0u};
    const HistoryAction action =
        keepHistory(graph, in, temporalHistory_, temporal, name(),
                    {{kHistShY, image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated SH luma, last frame")},
                     {kHistCoCgAo, image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated CoCg, AO, frame count, last frame")},
                     {kHistDepth, image(VK_FORMAT_R32_SFLOAT, "view depth, last frame")},
                     {kHistLumaMoment, image(VK_FORMAT_R32G32_SFLOAT,
                                             "mean squared sample luma, mean inverse hit distance, last frame")}})
            .action;
    restart_ = action == HistoryAction::Restart;
    push.lightChanged = action == HistoryAction::Reject ? 1u : 0u;
    push.disocclusionRays = std::min(s.rtDisocclusionRays, kMaxDisocclusionRays);
    push.hitSky = s.rtHitSky ? 1u : 0u;
    push.environmentSampling = s.rtEnvironmentSampling && hasEnvironmentMap(in) ? 1u : 0u;
    push.emitterCount = s.rtEmitterSampling ? scene_->emitterCount() : 0u;
    push.cameraWorld = glm::vec4(glm::vec3(in.cameraWorld), 0.0f);
    cache_.plan(graph, in, push, scene_->maxEmitterRadiance());
    push.maxAccumFrames = cache_.temporalWindow(push.maxAccumFrames);

    const bool screenRadiance = s.rtScreenRadiance;
    if (screenRadiance)
      graph.declarePersistent(kHistRadiance, image(kCompositeHdrFormat, "composite radiance, last frame"));

    // One ray per traced pixel, or two: the second's hit lighting writes the mean of both.
    push.raysPerPixel = s.rtTwoRays ? 2u : 1u;
    addRays(graph, in, push, kFirstRay, nullptr, screenRadiance);
    const RtRayResources* raw = s.rtTwoRays ? &kSecondRay : &kFirstRay;
    if (s.rtTwoRays) {
      RtPush second = push;
      second.sampleIndex = 1;
      addRays(graph, in, second, kSecondRay, &kFirstRay, screenRadiance);
    }

    addCacheUpdate(graph, in, push, screenRadiance);
    cache_.addPasses(graph, in);

    withCommon(ComputePass(in.device, "rt.temporal", "rt/temporal.comp"))
        .sampled(shared::kRtTemporalMotion, gbuffer::kMotion)
        .sampled(shared::kRtTemporalRawShY, raw->shY)
        .sampled(shared::kRtTemporalRawCoCg, raw->coCg)
        .sampled(shared::kRtTemporalRawAo, raw->ao)
        .sampled(shared::kRtTemporalHistoryShY, kHistShY)
        .sampled(shared::kRtTemporalHistoryCoCgAo, kHistCoCgAo)
        .sampled(shared::kRtTemporalHistoryViewDepth, kHistDepth)
        .sampled(shared::kRtTemporalHistoryMoment, kHistLumaMoment)
        .storageOut(shared::kRtTemporalOutShY, kShY,
                    image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated irradiance: L1 SH of luma")
                        .decodedAs(shIrradianceDecoder(kCoCgAo)))
        .storageOut(shared::kRtTemporalOutCoCgAo, kCoCgAo, image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated chroma (xy), AO (z), frames (w)"))
        .storageOut(shared::kRtTemporalOutViewDepth, kViewDepth,
                    image(VK_FORMAT_R32_SFLOAT, "view depth (w) for the next frame's disocclusion test"))
        .storageOut(shared::kRtTemporalOutMoment, kLumaMoment,
                    image(VK_FORMAT_R32G32_SFLOAT,
                          "mean squared sample luma (x: the firefly ceiling's and the denoiser's scale), mean inverse GI hit distance (y: the denoiser's radius)"))
        .push(push)
        // Whether the histories hold anything is known when the frame runs (their "stored" flags).
        .push(push,
              [this](graph::PassContext& ctx, RtPush& p) {
                p.historyValid = !restart_ && ctx.historyValid(kHistShY) && ctx.historyValid(kHistCoCgAo) &&
                                 ctx.historyValid(kHistDepth) && ctx.historyValid(kHistLumaMoment);
              })
        .dispatch(w, h)
        .add(graph);

    LightingOutputs out;
    // What the history, the AO filter and the denoiser take: the accumulation, with the
    // disocclusion rays filled into its fresh pixels when they are on.
    graph::ImageName accShY = kShY;
    graph::ImageName accCoCgAo = kCoCgAo;
    if (push.disocclusionRays > 0) {
      addDisocclusionPasses(graph, in, push, screenRadiance);
      accShY = kFilledShY;
      accCoCgAo = kFilledCoCgAo;
    }

    const bool reflections = s.rtReflectionRoughness > 0.0f;
    if (reflections) out.specular = addReflections(graph, in, push, screenRadiance);

    addCopyPass(graph, "rt.history",
                {{accShY, kHistShY}, {accCoCgAo, kHistCoCgAo}, {kViewDepth, kHistDepth}, {kLumaMoment, kHistLumaMoment}});

    withCommon(ComputePass(in.device, "rt.ao.filter", "rt/ao_filter.comp"))
        .sampled(shared::kRtAoFilterAccumulated, accCoCgAo)
        .sampled(shared::kRtAoFilterViewDepth, kViewDepth)
        .storageOut(shared::kRtAoFilterOut, kAo, image(VK_FORMAT_R16_SFLOAT, "filtered ambient occlusion").decodedAs("ao"))
        .push(push)
        .dispatch(w, h)
        .add(graph);

    if (s.rtRawRayProbe) {
      // The benchmark's trivial kernel, twice: every pixel's ray, and only the rays rt.trace
      // had to trace (the pre-trace's pending ones): the fair rate to hold rt.trace against.
      auto rawProbe = [&](const char* pass, graph::ImageName output, uint32_t pendingOnly) {
        RtPush probe = push;
        probe.rawPendingOnly = pendingOnly;
        withCommon(RayTracingPass(in.device, pass, kRawShaders))
            .accelerationStructure(shared::kRtBindingTlas, tlas(), structures())
            .storageIn(shared::kRtBindingHitsIn, kPretraceHits)
            .storageOut(shared::kRtRawDistances, output,
                        image(VK_FORMAT_R32_SFLOAT, "benchmark: hit distance of the trivial trace kernel"))
            .push(probe)
            .trace(tracedWidth(in), tracedHeight(in))
            .add(graph);
        graph.markOutput(output);
      };
      rawProbe("rt.rawRays", kRawRays, 0);
      rawProbe("rt.rawRays.pending", kRawRaysPending, 1);
    }

    if (screenRadiance) addCopyPass(graph, "rt.radiance.store", {{kCompositeHdr, kHistRadiance}});

    graph::ImageName giShY = accShY, giCoCg = accCoCgAo;
    if (s.rtDenoise) {
      const uint32_t frameIndex = in.constants.frameIndex;
      auto denoise = [&](const char* name, graph::ImageName inShY, graph::ImageName inCoCg, graph::ImageName outShY,
                         graph::ImageName outCoCg,
                         float radius, uint32_t normalWeight) {
        shared::RtDenoisePush dp{};
        dp.baseRadius = radius;
        dp.normalWeight = normalWeight;
        dp.rotation = goldenAngleRotation(frameIndex);
        dp.planeDistance = 0.02f;
        dp.hitDistanceCap = denoiseRadius;
        ComputePass(in.device, name, "rt/denoise.comp")
            .uniform(shared::kRtBindingFrame, kFrameConstants)
            .sampled(shared::kRtBindingDepth, gbuffer::kDepth)
            .sampled(shared::kRtBindingNormal, gbuffer::kNormal)
            .sampled(shared::kRtDenoiseInShY, inShY)
            .sampled(shared::kRtDenoiseInCoCgAo, inCoCg)
            .sampled(shared::kRtDenoiseLumaMoment, kLumaMoment)
            .sampled(shared::kRtBindingBaseColor, gbuffer::kBaseColor)
            .sampled(shared::kRtBindingMaterial, gbuffer::kMaterial)
            .storageOut(shared::kRtDenoiseOutShY, outShY,
                        image(VK_FORMAT_R16G16B16A16_SFLOAT, "denoised irradiance, SH luma")
                            .decodedAs(shIrradianceDecoder(outCoCg)))
            .storageOut(shared::kRtDenoiseOutCoCgAo, outCoCg,
                        image(VK_FORMAT_R16G16B16A16_SFLOAT, "denoised chroma (xy), AO and frames as input"))
            .push(dp)
            .dispatch(w, h)
            .add(graph);
      };
      denoise("rt.denoise1", accShY, accCoCgAo, kDenoise1ShY, kDenoise1CoCgAo, denoiseRadius, 0);
      denoise("rt.denoise2", kDenoise1ShY, kDenoise1CoCgAo, kDenoisedShY, kDenoisedCoCgAo, 0.5f * denoiseRadius, 1);
      giShY = kDenoisedShY;
      giCoCg = kDenoisedCoCgAo;
    }

    out.ambientOcclusion = kAo;
    out.diffuseShY = giShY;
    out.diffuseCoCg = giCoCg;
    out.giBlendDistance = params_.blendDistance;
    // The light table at the pixels: shadow rays against this top level (lights.direct).
    out.shadowStructures = structures();
    out.shadowTlasHandle = tlas();
    // Metro: beyond the blend distance, the legacy pipeline's GI. Its passes join the frame
    // only when some of the scene lies that far away; otherwise nobody pays for them.
    farLegacy_ = s.rtFarLegacy && farthestSceneDistance(in) > (1.0f - kGiBlendWidthFraction) * params_.blendDistance;
    if (farLegacy_) {
      if (!farField_) farField_ = makeLegacyPath();
      const LightingOutputs far = farField_->addPasses(graph, in);
      out.farShY = far.diffuseShY;
      out.farCoCg = far.diffuseCoCg;
      out.farAo = far.ambientOcclusion;
      out.farOpenSkyDirectionality = far.openSkyDirectionality;
    }
    return out;
  }

  // bench --rays: the rays rt.trace really traced (pixels its pre-trace left pending) against the
  // same rays through a trivial kernel (rt/raw.rgen), in the same frames.
  bool enableRayProbe(RenderSettings& settings) const override {
    settings.rtRawRayProbe = true;
    return true;
  }
  std::vector<std::string> rayProbeReadbacks() const override {
    return {std::string(kPretraceHits), std::string(gbuffer::kDepth)};
  }
  std::vector<std::pair<std::string, double>> rayFigures(const RayProbeFrame& frame) const override {
    const graph::Readback& pre = frame.readback(kPretraceHits);
    const std::vector<float> depth = frame.readback(gbuffer::kDepth).texels();
    std::vector<uint32_t> hits(pre.bytes.size() / 4);
    std::memcpy(hits.data(), pre.bytes.data(), hits.size() * 4);
    size_t surface = 0, pending = 0;
    const uint32_t w = frame.settings.width;
    const uint32_t pattern = rtRayPattern(frame.settings);
    for (size_t i = 0; i < hits.size() && i < depth.size(); ++i) {
      if (depth[i] <= 0.0f) continue;
      if (!shared::tlRtTracesThisFrame(glm::ivec2(int(i % w), int(i / w)), frame.frameIndex, pattern)) continue;
      ++surface;
      pending += shared::tlRtIsPending(hits[i]);
    }
    const double rawMs = frame.medianMs("rt.rawRays"), traceMs = frame.medianMs("rt.trace");
    const double rawPendingMs = frame.medianMs("rt.rawRays.pending");
    const double rawRate = RayProbeFrame::perSecond(double(surface), rawMs);
    const double rawPendingRate = RayProbeFrame::perSecond(double(pending), rawPendingMs);
    const double rtRate = RayProbeFrame::perSecond(double(pending), traceMs);
    const double pixels = double(frame.settings.width) * frame.settings.height;
    return {{"surfacePixels", double(surface)},  // traced this frame (all, this frame's checkerboard or 2x2 pixel)
            {"realRays", double(pending)},
            {"pretraceShare", surface ? 1.0 - double(pending) / double(surface) : 0.0},
            {"realRaysPerPixel", pending / pixels},
            {"rawKernelMs", rawMs},
            {"rawRaysPerSecond", rawRate},
            {"traceMs", traceMs},
            {"rtRaysPerSecond", rtRate},
            {"rtOverRaw", rawRate > 0.0 ? rtRate / rawRate : 0.0},
            // The same trivial kernel on only the rays rt.trace traced: those left after the
            // pre-trace are the long, incoherent ones, slower per ray for any kernel.
            {"rawPendingKernelMs", rawPendingMs},
            {"rawPendingRaysPerSecond", rawPendingRate},
            {"rtOverRawSameRays", rawPendingRate > 0.0 ? rtRate / rawPendingRate : 0.0}};
  }

  std::vector<std::pair<std::string, double>> figures() const override {
    if (!scene_) return {};
    const AccelStats& st = accelStats_;
    std::vector<std::pair<std::string, double>> out{{"tlasInstances", double(st.instancesInTopLevel)},
            {"sceneInstances", double(st.sceneInstances)},
            {"sourceTriangles", double(st.sourceTriangles)},
            {"rtTriangles", double(st.triangles)},
            {"blasBytes", double(st.blasBytes)},
            {"blasBuildMs", st.blasBuildMs},
            {"emitterTriangles", double(scene_->emitterCount())},
            {"simplificationDeviationM", double(st.maxDeviation)},
            {"farFieldLegacy", farLegacy_ ? 1.0 : 0.0},
            {"deformingMeshes", double(st.deformingMeshes)},
            {"blasStale", double(st.staleLastFrame)},
            {"blasRefits", double(st.refitsLastFrame)},
            {"blasRefitVertices", double(st.refitVerticesLastFrame)},
            {"aoRadiusM", double(params_.aoRadius)},
            {"rayLengthM", double(params_.rayLength)}};
    for (auto& f : cache_.figures()) out.push_back(std::move(f));
    return out;
  }

 private:
  // One ray per traced pixel: the screen-space pre-trace, real rays where it found nothing,
  // hit lighting into raw SH and AO. `first` is the first ray's set when this is the second.
  void addRays(graph::RenderGraph& graph, FrameInputs& in, const RtPush& push, const RtRayResources& r,
               const RtRayResources* first, bool screenRadiance) {
    auto image = [&](VkFormat f, std::string what) {
      return graph::ResourceDesc::image2D(f, in.settings.width, in.settings.height, std::move(what));
    };
    const char* rays = first ? "the mean of two rays" : "one ray";
    withCommon(ComputePass(in.device, r.pretracePass, "rt/pretrace.comp"))
        .sampled(shared::kRtBindingBaseColor, gbuffer::kBaseColor)
        .sampled(shared::kRtBindingMaterial, gbuffer::kMaterial)
        .sampled(shared::kRtBindingEmissive, gbuffer::kEmissive)
        .sampled(shared::kRtBindingInstanceId, gbuffer::kInstanceId)
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .storageOut(shared::kRtBindingHitsOut, r.pretraceHits,
                    image(VK_FORMAT_R32_UINT, "pre-trace hit records: distance + G-buffer albedo, or pending").decodedAs("rt-hit-record"))
        .storageOut(shared::kRtBindingSurfaceOut, r.pretraceSurface,
                    image(VK_FORMAT_R32G32_UINT, "pre-trace hit normal (oct) + emission (rgb9e5)").decodedAs("rt-hit-surface"))
        .push(push)
        .dispatch(tracedWidth(in), tracedHeight(in))
        .add(graph);

    withCommon(RayTracingPass(in.device, r.tracePass, kTraceShaders))
        .accelerationStructure(shared::kRtBindingTlas, tlas(), structures())
        .storageIn(shared::kRtBindingHitsIn, r.pretraceHits)
        .storageIn(shared::kRtBindingSurfaceIn, r.pretraceSurface)
        .storageOut(shared::kRtBindingHitsOut, r.hits,
                    image(VK_FORMAT_R32_UINT, "hit records: distance (half) + albedo (565), miss code").decodedAs("rt-hit-record"))
        .storageOut(shared::kRtBindingSurfaceOut, r.hitSurface,
                    image(VK_FORMAT_R32G32_UINT, "hit normal (oct) + emission (rgb9e5)").decodedAs("rt-hit-surface"))
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .sceneTable(in.scene.table())
        .push(push)
        .trace(tracedWidth(in), tracedHeight(in))
        .add(graph);

    withHitLighting(withCommon(RayTracingPass(in.device, r.lightingPass, kLightingShaders)), screenRadiance, in)
        .storageIn(shared::kRtBindingHitsIn, r.hits)
        .storageIn(shared::kRtBindingSurfaceIn, r.hitSurface)
        .storageOut(shared::kRtLightingOutShY, r.shY,
                    image(VK_FORMAT_R16G16B16A16_SFLOAT, fmt::format("{} irradiance: L1 SH of luma", rays))
                        .decodedAs(shIrradianceDecoder(r.coCg)))
        .storageOut(shared::kRtLightingOutCoCg, r.coCg, image(VK_FORMAT_R16G16_SFLOAT, fmt::format("{} irradiance: chroma", rays)))
        .storageOut(shared::kRtLightingOutAo, r.ao,
                    image(VK_FORMAT_R16G16_SFLOAT,
                          fmt::format("{} ambient occlusion (x: hit closer than the AO radius), hit distance up to the denoiser's radius (y)", rays)))
        // The first ray's results, read by the second ray only (lighting.rgen: RtPush::sampleIndex 1).
        .optionalSampled(shared::kRtLightingFirstShY, kFirstRay.shY, first != nullptr)
        .optionalSampled(shared::kRtLightingFirstCoCg, kFirstRay.coCg, first != nullptr)
        .optionalSampled(shared::kRtLightingFirstAo, kFirstRay.ao, first != nullptr)
        .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, push.environmentSampling != 0u)
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .push(push, screenRadianceAtRecord(screenRadiance))
        .trace(tracedWidth(in), tracedHeight(in))
        .add(graph);
  }

  // The radiance cache's update paths (rt/cache_update.rgen): every frame, also while the
  // cache is off (then a few one-ray probes), since their outcomes decide whether it runs.
  void addCacheUpdate(graph::RenderGraph& graph, FrameInputs& in, const RtPush& push, bool screenRadiance) {
    withHitLighting(withCommon(RayTracingPass(in.device, "rt.cache.update", kCacheUpdateShaders)), screenRadiance, in)
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .bufferOut(shared::kRtBindingCacheSamples, kRtCacheSamples, cache_.samplesDesc(in))
        .bufferOut(shared::kRtBindingCacheOutcomes, kRtCacheOutcomes, cache_.outcomesDesc(in))
        .push(push, screenRadianceAtRecord(screenRadiance))
        .trace(cache_.tilesX(in), cache_.tilesY(in))
        .add(graph);
    graph.markOutput(kRtCacheOutcomes);
  }

  // Ray-traced reflections (shared/rt_specular.h): one specular ray per pixel below the traced
  // roughness, its temporal accumulation by virtual motion, the lobe-sized filter. Returns the
  // image the composite reads.
  std::string addReflections(graph::RenderGraph& graph, FrameInputs& in, RtPush push, bool screenRadiance) {
    const RenderSettings& s = in.settings;
    const uint32_t w = s.width, h = s.height;
    auto image = [&](VkFormat f, const char* what) { return in.screenImage(f, what); };
    push.specularRoughness = shared::tlRtPackSpecularRoughness(s.rtReflectionRoughness, s.rtMirrorRoughness);
    // This pass's own pattern: the rough pixels' checkerboard (shared/rt_specular.h), not the GI's.
    push.rayPattern = s.rtReflectionRoughDivisor >= 2 ? shared::kRtRaysCheckerboard : shared::kRtRaysFull;
    const graph::ResourceDesc historyDesc = image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated reflections (rgb), frames (a), last frame");
    const graph::ResourceDesc historyHitDesc = image(VK_FORMAT_R16_SFLOAT, "accumulated reflection hit distance, last frame");
    graph.declarePersistent(kHistSpecular, historyDesc);
    graph.declarePersistent(kHistSpecularHit, historyHitDesc);

    withHitLighting(withCommon(RayTracingPass(in.device, "rt.specular", kSpecularShaders)), screenRadiance, in)
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, hasEnvironmentMap(in))
        .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
        .storageOut(shared::kRtBindingSpecularRaw, kSpecularRaw,
                    image(VK_FORMAT_R16G16B16A16_SFLOAT,
                          "one specular ray: radiance x lobe weight / lobe albedo (rgb), hit distance (a; 0 untraced)"))
        .push(push, screenRadianceAtRecord(screenRadiance))
        .trace(push.rayPattern == shared::kRtRaysCheckerboard ? (w + 1) / 2 : w, h)  // a pair an invocation (specular.rgen)
        .add(graph);

    shared::RtSpecularPush sp{};
    sp.maxFrames = float(s.rtReflectionFrames);
    sp.clampSigma = s.rtReflectionClamp;
    sp.specularRoughness = push.specularRoughness;
    sp.rotation = goldenAngleRotation(in.constants.frameIndex);
    sp.maxRadius = s.rtReflectionFilterRadius;
    sp.lightChanged = push.lightChanged;
    sp.roughDivisor = s.rtReflectionRoughDivisor >= 2 ? 2u : 1u;
    ComputePass(in.device, "rt.specular.temporal", "rt/specular_temporal.comp")
        .uniform(shared::kRtBindingFrame, kFrameConstants)
        .sampled(shared::kRtBindingDepth, gbuffer::kDepth)
        .sampled(shared::kRtBindingSpecularMotion, gbuffer::kMotion)
        .sampled(shared::kRtBindingMaterial, gbuffer::kMaterial)
        .sampled(shared::kRtBindingPreviousViewDepth, kHistDepth)
        .sampled(shared::kRtBindingSpecularRaw, kSpecularRaw)
        .sampled(shared::kRtBindingSpecularHistory, kHistSpecular, samplers::linear)
        .sampled(shared::kRtBindingSpecularHistoryHit, kHistSpecularHit, samplers::linear)
        .storageOut(shared::kRtBindingSpecularAccumulated, kSpecularTemporal,
                    image(VK_FORMAT_R16G16B16A16_SFLOAT, "accumulated reflections, demodulated (rgb), frames (a)"))
        .storageOut(shared::kRtBindingSpecularHit, kSpecularHitDistance,
                    image(VK_FORMAT_R16_SFLOAT, "accumulated reflection hit distance (the filter's footprint)"))
        .push(sp)
        .push(sp,
              [this](graph::PassContext& ctx, shared::RtSpecularPush& p) {
                p.historyValid = !restart_ && ctx.historyValid(kHistSpecular) && ctx.historyValid(kHistSpecularHit) &&
                                 ctx.historyValid(kHistDepth);
              })
        .dispatch(w, h)
        .add(graph);
    addCopyPass(graph, "rt.specular.history", {{kSpecularTemporal, kHistSpecular}, {kSpecularHitDistance, kHistSpecularHit}});

    ComputePass(in.device, "rt.specular.filter", "rt/specular_filter.comp")
        .uniform(shared::kRtBindingFrame, kFrameConstants)
        .sampled(shared::kRtBindingDepth, gbuffer::kDepth)
        .sampled(shared::kRtBindingNormal, gbuffer::kNormal)
        .sampled(shared::kRtBindingMaterial, gbuffer::kMaterial)
        .sampled(shared::kRtBindingSpecularAccumulated, kSpecularTemporal)
        .sampled(shared::kRtBindingSpecularHit, kSpecularHitDistance)
        .storageOut(shared::kRtBindingSpecularFiltered, kSpecular,
                    image(VK_FORMAT_R16G16B16A16_SFLOAT,
                          "reflections, filtered by the lobe's footprint, demodulated (rgb); weight against the SH specular (a)"))
        .push(sp)
        .dispatch(w, h)
        .add(graph);
    return std::string(kSpecular);
  }

  static constexpr uint32_t kMaxDisocclusionRays = 64;  // RE ENGINE traces 16-64 per low-resolution pixel

  // Disocclusion rays (shared/rt.h): cells with a fresh pixel trace many rays, then the fresh
  // pixels take them into the accumulation.
  void addDisocclusionPasses(graph::RenderGraph& graph, FrameInputs& in, const RtPush& push, bool screenRadiance) {
    const uint32_t cw = cellsAcross(in.settings.width), ch = cellsAcross(in.settings.height);
    auto cells = [&](VkFormat f, const char* what) { return graph::ResourceDesc::image2D(f, cw, ch, what); };
    withHitLighting(withCommon(RayTracingPass(in.device, "rt.disocclusion", kDisocclusionShaders)), screenRadiance, in)
        .sampled(shared::kRtDisocclusionAccumulated, kCoCgAo)
        .constantBuffer(shared::kRtBindingInstances, scene_->instanceData(in.frame).handle())
        .storageOut(shared::kRtDisocclusionCellShY, kCellShY,
                    cells(VK_FORMAT_R16G16B16A16_SFLOAT, "disocclusion rays per 8x8 cell: mean SH luma"))
        .storageOut(shared::kRtDisocclusionCellCoCgAo, kCellCoCgAo,
                    cells(VK_FORMAT_R16G16B16A16_SFLOAT, "disocclusion rays: mean chroma (xy), AO (z)"))
        .storageOut(shared::kRtDisocclusionCellOrigin, kCellOrigin,
                    cells(VK_FORMAT_R32G32B32A32_SFLOAT, "disocclusion rays: world origin (xyz), 1 if traced (w)"))
        .optionalBufferIn(shared::kBindingEnvironment, kEnvironmentTable, push.environmentSampling != 0u)
        .push(push, screenRadianceAtRecord(screenRadiance))
        .trace(cw, ch)
        .add(graph);
    const uint32_t w = in.settings.width, h = in.settings.height;
    withCommon(ComputePass(in.device, "rt.disocclusion.blend", "rt/disocclusion_blend.comp"))
        .sampled(shared::kRtBlendAccumulatedShY, kShY)
        .sampled(shared::kRtBlendAccumulatedCoCgAo, kCoCgAo)
        .sampled(shared::kRtBlendCellShY, kCellShY)
        .sampled(shared::kRtBlendCellCoCgAo, kCellCoCgAo)
        .sampled(shared::kRtBlendCellOrigin, kCellOrigin)
        .storageOut(shared::kRtBlendOutShY, kFilledShY,
                    in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                   "accumulated irradiance, fresh pixels filled from the disocclusion rays")
                        .decodedAs(shIrradianceDecoder(kFilledCoCgAo)))
        .storageOut(shared::kRtBlendOutCoCgAo, kFilledCoCgAo,
                    in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                   "accumulated chroma (xy), AO (z), frames (w), fresh pixels filled"))
        .push(push)
        .dispatch(w, h)
        .add(graph);
  }
  static uint32_t cellsAcross(uint32_t pixels) {
    return (pixels + shared::kRtDisocclusionCell - 1) / shared::kRtDisocclusionCell;
  }

  // What a trace reads: the top level and, through it, the bottom levels a frame may rewrite.
  const std::vector<std::string>& structures() const { return structures_.names; }
  VkAccelerationStructureKHR tlas() const { return structures_.tlas; }

  // What shading a hit reads (rt/hit_lighting.glsl): the top level, last frame's image and
  // depth for hits seen on screen, the G-buffer's material there, the emitters, the light
  // table and the radiance cache. Those the frame may lack are optional: the shader reads last
  // frame's image only with RtPush::screenRadiance (0 without it), the cache only with
  // RtPush::cacheLookup (0 while it is off), the light table only for frame.lightCount > 0.
  RayTracingPass withHitLighting(RayTracingPass pass, bool screenRadiance, const FrameInputs& in) const {
    pass.accelerationStructure(shared::kRtBindingTlas, tlas(), structures())
        .constantBuffer(shared::kRtBindingEmitters, scene_->emitterData().handle())
        .optionalBufferIn(shared::kRtBindingCacheEntries, kRtCacheEntries, cache_.active())
        .optionalBufferIn(shared::kBindingLights, kLightTable, in.constants.lightCount > 0)
        .optionalSampled(shared::kRtBindingPreviousRadiance, kHistRadiance, screenRadiance)
        .sampled(shared::kRtBindingPreviousViewDepth, kHistDepth)
        .sampled(shared::kRtBindingBaseColor, gbuffer::kBaseColor)
        .sampled(shared::kRtBindingMaterial, gbuffer::kMaterial)
        .sampled(shared::kRtBindingEmissive, gbuffer::kEmissive)
        .sceneTable(in.scene.table());
    return pass;
  }
  // Last frame's image shows the old light: when the light changed, hits are lit afresh (else
  // the luminance rejection would clip the history to samples of the old light).
  static uint32_t useScreenRadiance(graph::PassContext& ctx, const RtPush& push, bool screenRadiance) {
    return screenRadiance && push.lightChanged == 0u && ctx.historyValid(kHistRadiance) && ctx.historyValid(kHistDepth)
               ? shared::kRtScreenRadianceUsed
               : shared::kRtScreenRadianceUnavailable;
  }
  // The same as the pass records (when the histories' "stored" flags are known).
  std::function<void(graph::PassContext&, RtPush&)> screenRadianceAtRecord(bool screenRadiance) {
    // While the radiance cache runs, hits are lit afresh and read it: last frame's image lags
    // behind its own accumulation window, and where bounced light matters (which is where the
    // cache runs) that lag held the image down (a white room lit through slits: 0.68 of the
    // reference after 64 frames with the image, 0.76 with the cache alone; docs/accuracy.md).
    // This frame's state, taken now: the pass records after the next frame may have begun.
    const bool reads = screenRadiance && !cache_.active(), restarted = restart_;
    return [reads, restarted](graph::PassContext& ctx, RtPush& p) {
      p.screenRadiance = reads ? useScreenRadiance(ctx, p, !restarted) : shared::kRtScreenRadianceOff;
    };
  }

  // From the camera to the farthest corner of the scene's bounds.
  static double farthestSceneDistance(const FrameInputs& in) {
    const auto& b = in.sceneData.bounds;
    if (!b.valid()) return 0.0;
    double farthest = 0.0;
    for (int c = 0; c < 8; ++c) farthest = std::max(farthest, glm::length(b.corner(c) - in.cameraWorld));
    return farthest;
  }

  // What the shaders declare in rt/rt_common.glsl, on a compute or ray-tracing pass's list.
  template <class Pass>
  Pass withCommon(Pass pass) const {
    pass.uniform(shared::kRtBindingFrame, kFrameConstants)
        .constantSampled(shared::kRtBindingBlueNoise, blueNoise_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .sampled(shared::kRtBindingDepth, gbuffer::kDepth)
        .sampled(shared::kRtBindingNormal, gbuffer::kNormal);
    return pass;
  }
  // Invocations per row of the passes that trace: half with 0.5 rays per pixel.
  static uint32_t tracedWidth(const FrameInputs& in) {
    return rtRayPattern(in.settings) == shared::kRtRaysFull ? in.settings.width : (in.settings.width + 1) / 2;
  }
  static uint32_t tracedHeight(const FrameInputs& in) {
    return rtRayPattern(in.settings) == shared::kRtRaysHalfResolution ? (in.settings.height + 1) / 2 : in.settings.height;
  }

  // The hits' scene data and blue noise: once per build of the simplified structures (a scene,
  // an RT mesh ratio). The pipelines are the device's (RayTracingPass), built at their first
  // frame and kept across scenes.
  void prepare(FrameInputs& in) {
    const uint64_t generation = in.accel->generation(AccelDetail::Simplified);
    if (!scene_ || accelGeneration_ != generation) {
      in.device.waitIdle();
      scene_ = std::make_unique<RtScene>(in.device, in.sceneData, in.scene, in.accel->meshIndices(AccelDetail::Simplified));
      accelGeneration_ = generation;
      albedoVersion_ = ~0ull;
    }
    const uint32_t materials = uint32_t(in.settings.materials);
    if (albedoVersion_ != in.instanceAlbedoVersion || materials_ != materials) {
      scene_->setInstanceAlbedo(in.instanceAlbedo, materials, in.frame);  // an override shows in the next frame's bounce
      albedoVersion_ = in.instanceAlbedoVersion;
      materials_ = materials;
    }
    if (blueNoise_) return;
    // Two independent masks, one per uniform of the ray's direction.
    static const std::vector<uint16_t> maskU = voidAndClusterRanks(shared::kRtBlueNoiseSize, 1);
    static const std::vector<uint16_t> maskV = voidAndClusterRanks(shared::kRtBlueNoiseSize, 2);
    const uint32_t n = shared::kRtBlueNoiseSize;
    std::vector<uint16_t> texels(2 * n * n);
    // Rank r -> (r + 0.5) / n^2 in unorm16: uniform in (0, 1).
    for (uint32_t i = 0; i < n * n; ++i) {
      texels[2 * i] = uint16_t((uint32_t(maskU[i]) * 2 + 1) * 65535u / (2 * n * n));
      texels[2 * i + 1] = uint16_t((uint32_t(maskV[i]) * 2 + 1) * 65535u / (2 * n * n));
    }
    blueNoise_ = gpu::Image(in.device,
                            {VK_FORMAT_R16G16_UNORM, {n, n, 1}, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                            "rt.blueNoise");
    gpu::uploadImage2D(in.device, blueNoise_, texels.data(), texels.size() * sizeof(uint16_t));

  }

  std::unique_ptr<RtScene> scene_;
  TraceStructures structures_;  // this frame's, borrowed from the SceneAccel
  AccelStats accelStats_;
  uint64_t accelGeneration_ = 0;  // the build of the structures scene_ was made for
  std::unique_ptr<LightingPath> farField_;  // the legacy path, for GI beyond the blend distance
  bool farLegacy_ = false;
  uint64_t albedoVersion_ = ~0ull;
  uint32_t materials_ = 0;  // the material override mode the instance albedos were set for
  HistoryKeeper temporalHistory_;
  bool restart_ = false;  // this frame drops the temporal history (a cut, a new scene, a setting)
  RtResolvedParams params_;
  gpu::Image blueNoise_;
  RtRadianceCache cache_;
};

}  // namespace

std::unique_ptr<LightingPath> makeRtPath() { return std::make_unique<RtPath>(); }

}  // namespace tl::lighting
