// The legacy lighting path ("RTX OFF"): horizon-based SSAO (GTAO) at half resolution, a voxel
// clipmap voxelized from the scene's triangles with the sun injected through the shadow map
// (kept while nothing it holds changes; when only some instances deform or move, only the
// voxels they and their shadows reach are redone, as VXAO does), its mip chain, six diffuse
// cones per pixel for irradiance (in the RT path's SH layout) and voxel AO from the same
// cones, the SSAO's temporal accumulation at its own resolution, then a depth-aware upsample.
// Every intermediate is a named graph resource.
#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/decoders.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/history.h"
#include "lighting/common/shadow_pass.h"
#include "lighting/legacy/legacy_path.h"
#include "lighting/legacy/voxel_regions.h"
#include "lighting/lighting_path.h"
#include "lighting/common/light_table.h"
#include "lighting/common/light_shadows.h"
#include "lighting/common/lights_pass.h"
#include "lighting/common/pass_builders.h"
#include "shared/brdf_lut.h"
#include "shared/legacy_reflections.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

namespace tl::lighting {
namespace {

using graph::Usage;
using shared::LegacyPush;
using shared::LegacyVoxelPush;

// What the voxels get this frame: nothing, a rebuild, or a partial update of some regions.
// Per level, the regions to redo (a rebuild's is the whole level) and, per region, the
// instances that can write into it, in scene order (the full rebuild's draw order).
struct VoxelWork {
  enum class Kind { Keep, Partial, Full };
  Kind kind = Kind::Keep;
  std::vector<std::vector<VoxelRegion>> regions;
  std::vector<std::vector<std::vector<uint32_t>>> instances;
  uint32_t instancesDrawn = 0;  // distinct instances voxelized
  int64_t regionVoxels = 0;     // voxels per face block cleared and voxelized, all levels
  size_t regionCount() const {
    size_t n = 0;
    for (const auto& r : regions) n += r.size();
    return n;
  }
};

// Which of a region's instances a voxelization round draws.
enum class DrawSet { All, Plain, Emissive };

// A partial update costing more than this fraction of a rebuild's voxels rebuilds instead:
// its per-region draws and dispatches would no longer pay for themselves.
constexpr double kPartialVoxelBudget = 0.5;

// The voxels hold world-space light: the sun injected through the shadow map, emission and,
// with screen feedback, the light of the last frames (so the sky too). A new sun, scene or
// setting rebuilds them, and so does a camera move that shifts their placement in the world;
// geometry that deforms or moves is patched where it reaches (takeInstanceChanges).
constexpr FrameParts kVoxelRestarts = parts(FramePart::Sun, FramePart::Scene, FramePart::Settings);
// The screen-space histories, SSAO's accumulation and the last frame's radiance and depth the
// voxelization reuses: reprojected as the camera moves, restarted by a cut, a new scene or a
// setting.
constexpr HistoryPolicy kScreenHistory{"legacy.ssao", parts(FramePart::Scene, FramePart::Settings, FramePart::CameraCut), 0};

class LegacyPath final : public LightingPath {
 public:
  std::string name() const override { return "legacy"; }
  PathCapabilities capabilities() const override { return {.accumulates = true}; }
  std::string description() const override {
    return "RTX OFF: GTAO + voxel clipmap GI with cone tracing and voxel AO";
  }

  std::vector<std::pair<std::string, double>> figures() const override {
    return {{"voxelUpdate", double(int(lastWork_.kind))},  // 0 kept, 1 partial, 2 rebuilt
            {"voxelizedInstances", double(lastWork_.instancesDrawn)},
            {"voxelRegions", double(lastWork_.regions)},
            {"voxelRegionVoxels", double(lastWork_.regionVoxels)}};
  }

  LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) override {
    prepare(in);
    const RenderSettings& s = in.settings;
    const LegacyClipmapFit fit = fitLegacyClipmap(in.sceneData.bounds, in.cameraWorld, s.legacyVoxelResolution,
                                                  s.legacyLevel0Extent, s.legacyMaxLevels);
    LegacyPush push{};
    push.clipmap = fit.clipmap;
    push.aoRadius = s.legacyAoRadius;  // in.settings has automatic values resolved
    push.aoThickness = std::clamp(s.legacyAoThickness, 0.0f, 1.0f);
    push.aoSlices = std::max(1u, s.legacyAoSlices);
    push.aoSteps = std::max(1u, s.legacyAoSteps);
    push.coneRange = s.legacyConeRange;
    push.coneStep = std::clamp(s.legacyConeStep, 0.2f, 2.0f);
    push.aoDivisor = s.legacyAoDivisor >= 2 ? 2u : 1u;
    push.coneDivisor = s.legacyConeDivisor >= 4 ? 4u : (s.legacyConeDivisor >= 2 ? 2u : 1u);

    const uint32_t w = s.width, h = s.height;
    const uint32_t aw = (w + push.aoDivisor - 1) / push.aoDivisor, ah = (h + push.aoDivisor - 1) / push.aoDivisor;
    const uint32_t cw = (w + push.coneDivisor - 1) / push.coneDivisor, ch = (h + push.coneDivisor - 1) / push.coneDivisor;
    const uint32_t R = fit.clipmap.resolution, N = fit.clipmap.levels, mips = fit.clipmap.mipCount;

    withCommon(ComputePass(in.device, "legacy.ssao", "legacy/ssao.comp"))
        .storageOut(shared::kLegacyBindingAoRaw, kLegacyAoRaw,
                    graph::ResourceDesc::image2D(VK_FORMAT_R16G16_SFLOAT, aw, ah, "GTAO visibility (r) and view depth (g), 1/aoDivisor")
                        .decodedAs("ao"))
        .push(push)
        .dispatch(aw, ah)
        .add(graph);

    // The voxels persist: they are rebuilt only when what they hold changes (where the levels
    // sit in the world, the sun, the settings), so a still camera pays nothing for them; when
    // only some instances changed, only the voxels those reach are redone.
    const std::vector<scene::Bounds> changes = takeInstanceChanges(in);
    const graph::ResourceDesc voxelDesc = graph::ResourceDesc::image3D(
        VK_FORMAT_R16G16B16A16_SFLOAT, 6 * R, R, N * R,
        fmt::format("voxels per face (+x -x +y -y +z -z blocks along x): radiance, opacity; {} level(s) of {}^3 stacked in z",
                    N, R)).decodedAs("voxel-faces");
    const graph::ResourceDesc voxelMipsDesc =
        graph::ResourceDesc::image3D(VK_FORMAT_R16G16B16A16_SFLOAT, 3 * R, R / 2, N * R / 2,
                                     "voxels per face, mips 1.. (front-to-back along each face's axis)", mips);
    const graph::ResourceDesc radianceDesc = in.screenImage(kCompositeHdrFormat, "composite radiance, last frame");
    const graph::ResourceDesc depthDesc = in.screenImage(VK_FORMAT_D32_SFLOAT, "G-buffer depth, last frame");
    // The SSAO accumulates at its own resolution, before the upsample: a quarter of the pixels.
    // It keeps the view depth it was taken at, so the next frame's history test needs no depth.
    const graph::ResourceDesc ssaoDesc = graph::ResourceDesc::image2D(
        VK_FORMAT_R16G16B16A16_SFLOAT, aw, ah, "GTAO accumulated (r), view depth (g), frames (b), 1/aoDivisor, last frame");
    graph.declareCache(kVoxelRadiance, voxelDesc);
    graph.declareCache(kVoxelRadianceMips, voxelMipsDesc);
    // Rooms: the finest level's air that light reaches, redone with the voxels (shared/legacy.h).
    const bool rooms = s.legacyRoomSweeps > 0;
    push.clipmap.roomGate = rooms ? 1u : 0u;
    const graph::ResourceDesc seedsDesc = graph::ResourceDesc::image3D(
        VK_FORMAT_R8_UINT, R, R, R, "rooms: 1 where an empty voxel of the finest level faces a directly lit surface");
    const graph::ResourceDesc reachDesc = graph::ResourceDesc::image3D(
        VK_FORMAT_R8_UINT, R, R, R, "rooms: the finest level's voxels, 0 sealed air, 1 air light reaches, 2 solid");
    const graph::ResourceDesc unsettledDesc =
        graph::ResourceDesc::buffer(sizeof(uint32_t), "rooms: voxels the flood's last round still reached (0: settled)");
    if (rooms) {
      graph.declareCache(kVoxelSeeds, seedsDesc);
      graph.declareCache(kVoxelReach, reachDesc);
      graph.declareCache(kVoxelReachUnsettled, unsettledDesc);
    }
    const bool feedback = s.legacyScreenRadiance;
    if (feedback) {  // only the voxelization reads these
      graph.declarePersistent(kLegacyHistRadiance, radianceDesc);
      graph.declarePersistent(kLegacyHistDepth, depthDesc);
    }
    // History counts only if this frame's declaration keeps it: a resize recreates it with
    // undefined contents (NaN on lavapipe's reused memory, once), and restarts it.
    const bool screenKept = keepHistory(graph, in, screen_, kScreenHistory, name(), {{kLegacyHistSsao, ssaoDesc}}).action !=
                            HistoryAction::Restart;
    const bool aoHistory = s.legacyAoFrames > 1 && screenKept;
    push.aoHistory = aoHistory ? s.legacyAoFrames : 0u;

    withCommon(ComputePass(in.device, "legacy.ssao.temporal", "legacy/ssao_temporal.comp"))
        .sampled(shared::kLegacyBindingAoRaw, kLegacyAoRaw)
        .sampled(shared::kLegacyBindingAoHistory, kLegacyHistSsao)
        .sampled(shared::kLegacyBindingMotion, gbuffer::kMotion)
        .storageOut(shared::kLegacyBindingSsaoOut, kLegacySsao,
                    graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, aw, ah,
                                                 "GTAO accumulated over frames (r), view depth (g), frames (b), 1/aoDivisor")
                        .decodedAs("ao"))
        .push(push)
        .dispatch(aw, ah)
        .add(graph);
    const bool historyOk = feedback && screenKept && in.historyValid(kLegacyHistRadiance, radianceDesc) &&
                           in.historyValid(kLegacyHistDepth, depthDesc);
    const bool voxelsKept = in.historyValid(kVoxelRadiance, voxelDesc) && in.historyValid(kVoxelRadianceMips, voxelMipsDesc) &&
                            (!rooms || (in.historyValid(kVoxelSeeds, seedsDesc) && in.historyValid(kVoxelReach, reachDesc) &&
                                        in.historyValid(kVoxelReachUnsettled, unsettledDesc)));
    // The voxels hold this placement, sun and settings: a change of some instances can be
    // patched into them.
    const std::vector<glm::dvec4> placement = voxelPlacement(in, fit);
    const HistoryPolicy voxelPolicy{"legacy.voxels", kVoxelRestarts | (feedback ? partBit(FramePart::Sky) : 0u), 0};
    const FrameParts moved = placement != placement_ ? partBit(FramePart::CameraPosition) : 0u;
    const bool placed =
        voxels_.advance(voxelPolicy, in.key, name(), in.historyLog, {voxelsKept, moved}).action != HistoryAction::Restart;
    placement_ = placement;
    push.screenRadiance = historyOk ? 1u : 0u;
    const auto work = std::make_shared<VoxelWork>(planVoxelUpdate(in, fit, changes, placed, historyOk));
    lastWork_ = {work->kind, work->instancesDrawn, work->regionVoxels, uint32_t(work->regionCount())};
    if (work->kind != VoxelWork::Kind::Keep) {
      addVoxelPasses(graph, in, push.clipmap, work, feedback, push.screenRadiance);
      if (rooms) addRoomPasses(graph, in, push.clipmap, s.legacyRoomSweeps);
    }

    withVoxelCones(withCommon(ComputePass(in.device, "legacy.cones", "legacy/cones.comp")), rooms)
        .storageOut(shared::kLegacyBindingConeShY, kConeShY,
                    graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, cw, ch, "cone-traced irradiance, SH luma")
                        .decodedAs(shIrradianceDecoder(kConeCoCgAo)))
        .storageOut(shared::kLegacyBindingConeCoCgAo, kConeCoCgAo,
                    graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, cw, ch,
                                                 "cone-traced chroma (xy), voxel AO (z), view depth (w)"))
        .push(push)
        .dispatch(cw, ch)
        .add(graph);

    withCommon(ComputePass(in.device, "legacy.upsample", "legacy/upsample.comp"))
        .sampled(shared::kLegacyUpsampleSsao, kLegacySsao, samplers::linear)
        .sampled(shared::kLegacyBindingConeShY, kConeShY, samplers::linear)
        .sampled(shared::kLegacyBindingConeCoCgAo, kConeCoCgAo, samplers::linear)
        .storageOut(shared::kLegacyBindingOutAo, kLegacyAo,
                    in.screenImage(VK_FORMAT_R16_SFLOAT, "AO: GTAO x voxel AO").decodedAs("ao"))
        .storageOut(shared::kLegacyBindingOutShY, kLegacyShY,
                    in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT, "diffuse irradiance, SH luma")
                        .decodedAs(shIrradianceDecoder(kLegacyCoCg)))
        .storageOut(shared::kLegacyBindingOutCoCg, kLegacyCoCg,
                    in.screenImage(VK_FORMAT_R16G16_SFLOAT, "diffuse irradiance, chroma"))
        .push(push)
        .dispatch(w, h)
        .add(graph);

    const bool reflections = s.legacyReflectionRoughness > 0.0f;
    if (reflections) addReflections(graph, in, push, rooms, feedback, historyOk);

    std::vector<ImageCopy> history = {{kLegacySsao, kLegacyHistSsao}};
    if (feedback) {
      history.push_back({gbuffer::kDepth, kLegacyHistDepth});
      history.push_back({kCompositeHdr, kLegacyHistRadiance});
    }
    addCopyPass(graph, "legacy.history", std::move(history));

    LightingOutputs out;
    out.ambientOcclusion = kLegacyAo;
    out.diffuseShY = kLegacyShY;
    out.diffuseCoCg = kLegacyCoCg;
    out.aoOnGi = true;
    if (reflections) out.specular = kLegacyReflections;
    out.openSkyDirectionality = shared::tlLegacyOpenSkyDirectionality();
    return out;
  }

 private:
  // Reflections (shared/legacy_reflections.h): the hierarchical depth, a mip per pass, then
  // one pass that marches the screen and traces the voxels' specular cone. Last frame's image
  // and depth are bound only when the voxels' feedback keeps them; `screen` says they hold
  // last frame.
  static uint32_t mipSide(uint32_t side, uint32_t mip) { return std::max(side >> mip, 1u); }  // Vulkan's mip sizes
  static void addReflections(graph::RenderGraph& graph, FrameInputs& in, const LegacyPush& push, bool rooms,
                             bool feedback, bool screen) {
    const RenderSettings& s = in.settings;
    const uint32_t w = s.width, h = s.height;
    uint32_t mips = 1;
    while (mips < shared::kLegacyHizMaxMips && (std::max(w, h) >> mips) > 0) ++mips;
    shared::LegacyReflectionPush rp{};
    rp.clipmap = push.clipmap;
    rp.roughness = s.legacyReflectionRoughness;
    rp.coneRange = push.coneRange;
    rp.coneStep = push.coneStep;
    rp.screenHistory = screen ? 1u : 0u;
    rp.hizMips = mips;
    rp.maxSteps = s.legacyReflectionSteps;

    ComputePass(in.device, "legacy.reflections.hiz0", "legacy/hiz_first.comp")
        .uniform(shared::kLegacyBindingFrame, kFrameConstants)
        .sampled(shared::kLegacyBindingDepth, gbuffer::kDepth)
        .storageOut(
            shared::kLegacyBindingHizOut, kLegacyHiz,
            in.screenImage(VK_FORMAT_R32_SFLOAT,
                           "hierarchical depth: the nearest reversed-Z depth of each 2^m-pixel cell, mip m", mips),
            0)
        .dispatch(w, h)
        .add(graph);
    for (uint32_t m = 1; m < mips; ++m) {
      ComputePass(in.device, fmt::format("legacy.reflections.hiz{}", m), "legacy/hiz_reduce.comp")
          .storageIn(shared::kLegacyBindingHizSource, kLegacyHiz, m - 1)
          .storageUpdate(shared::kLegacyBindingHizOut, kLegacyHiz, m)
          .pipelineName("legacy.reflections.hiz")
          .dispatch(mipSide(w, m), mipSide(h, m))
          .add(graph);
    }

    // The march and the cone, every pixel; or one of each 2x2 block, then the upsample
    // (shared/legacy_reflections.h: one shader, its mode in the push constants).
    auto reflectionPass = [&](const char* name, uint32_t mode) {
      rp.mode = mode;
      ComputePass pass = withVoxelCones(withCommon(ComputePass(in.device, name, "legacy/reflections.comp")), rooms);
      pass.pipelineName("legacy.reflections")
          .sampled(shared::kLegacyBindingMaterial, gbuffer::kMaterial)
          .sampled(shared::kLegacyBindingBaseColor, gbuffer::kBaseColor)
          .bufferIn(shared::kBindingBrdfTables, kBrdfTables)
          .sampled(shared::kLegacyBindingHiz, kLegacyHiz)
          .optionalSampled(shared::kLegacyBindingPrevRadiance, kLegacyHistRadiance, feedback, samplers::linear)
          .optionalSampled(shared::kLegacyBindingPrevDepth, kLegacyHistDepth, feedback)
          .optionalSampled(shared::kLegacyBindingReflectionsReduced, kLegacyReflectionsReduced,
                           mode == shared::kLegacyReflectionsUpsample)
          .push(rp);
      return pass;
    };
    const auto fullDesc = in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                         "reflections: screen-space march and voxel cone, demodulated (rgb); weight "
                                         "against the SH specular (a)");
    if (s.legacyReflectionDivisor < 2) {
      reflectionPass("legacy.reflections", shared::kLegacyReflectionsFull)
          .storageOut(shared::kLegacyBindingReflections, kLegacyReflections, fullDesc)
          .dispatch(w, h)
          .add(graph);
      return;
    }
    const uint32_t rw = (w + 1) / 2, rh = (h + 1) / 2;
    rp.fullRoughness = s.legacyMirrorRoughness;
    reflectionPass("legacy.reflections.reduced", shared::kLegacyReflectionsReduced)
        .storageOut(shared::kLegacyBindingReflections, kLegacyReflectionsReduced,
                    graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, rw, rh,
                                                 "reflections of one pixel of each 2x2 block (its top-left): march "
                                                 "and cone, demodulated (rgb); 1 where it reflects (a)"))
        .dispatch(rw, rh)
        .add(graph);
    reflectionPass("legacy.reflections", shared::kLegacyReflectionsUpsample)
        .storageOut(shared::kLegacyBindingReflections, kLegacyReflections, fullDesc)
        .dispatch(w, h)
        .add(graph);
  }

  // The voxel work over the work's regions (whole levels for a rebuild), as steps of one
  // write each of the voxels and their mips, which the graph orders and fences: the regions
  // emptied, voxelized in up to three rounds, then the mips, a level per pass.
  void addVoxelPasses(graph::RenderGraph& graph, FrameInputs& in, const shared::LegacyClipmap& clipmap,
                      std::shared_ptr<const VoxelWork> work, bool feedback, uint32_t screenRadiance) {
    const uint32_t R = clipmap.resolution, mips = clipmap.mipCount;
    const bool rooms = clipmap.roomGate != 0;
    LegacyVoxelPush vpush{};
    vpush.clipmap = clipmap;
    vpush.screenRadiance = screenRadiance;

    // The voxels start empty: a rebuild's by a transfer clear of the whole image (a compute
    // clear costs 10 ms more on lavapipe), a patch's in all six face blocks of each region. The
    // rooms' seeds are emptied by a rebuild only: a patch adds the seeds of what it redraws and
    // keeps the rest (a surface outside a region can seed the voxel in front of it inside; a
    // seed left where light no longer enters only lets light into a room, never darkens one,
    // until the rebuilds that settle the bounces once the geometry stops).
    if (work->kind == VoxelWork::Kind::Full) {
      TransferPass clear("legacy.voxel.clear");
      clear.clear(kVoxelRadiance);
      if (rooms) clear.clear(kVoxelSeeds);
      clear.add(graph);
    } else {
      ComputePass clear(in.device, "legacy.voxel.clear", "legacy/voxel_clear.comp");
      clear.storageOut(shared::kLegacyBindingRadiance, kVoxelRadiance);
      clear.push(vpush)
          .record([vpush, work](graph::PassContext& ctx) { dispatchOverRegions(ctx, vpush, *work, 0); })
          .add(graph);
    }

    // Round 0 makes every touched voxel opaque on all faces; round 1 writes the faces each
    // surface looks out of; emitters come last, in a pass of their own, so where an emitter
    // shares a voxel with a dark surface (a light panel under a ceiling) the emitter wins.
    struct Round {
      const char* name;
      uint32_t mode;
      DrawSet set;
      const std::vector<uint32_t>* instances;
    };
    const Round rounds[] = {{"legacy.voxelize", 0, DrawSet::All, &allInstances_},
                            {"legacy.voxelize.faces", 1, DrawSet::Plain, &plainInstances_},
                            {"legacy.voxelize.emitters", 1, DrawSet::Emissive, &emissiveInstances_}};
    // The seeds' first writer this frame: the clear in a rebuild, else the first round drawn.
    SeedsAccess seeds = !rooms ? SeedsAccess::Absent : (work->kind == VoxelWork::Kind::Full ? SeedsAccess::Update : SeedsAccess::Write);
    for (const Round& round : rounds) {
      if (round.instances->empty()) continue;
      vpush.voxelRound = round.mode;
      RasterPass pass = voxelizePass(in, round.name, vpush, feedback, seeds, R);
      if (seeds == SeedsAccess::Write) seeds = SeedsAccess::Update;
      pass
          .draw([this, &in, vpush, work, set = round.set](graph::PassContext& ctx, const RasterPass::Use&) mutable {
            std::vector<uint32_t> draw;
            for (uint32_t level = 0; level < work->regions.size(); ++level)
              for (size_t r = 0; r < work->regions[level].size(); ++r) {
                selectInstances(work->instances[level][r], set, draw);
                if (draw.empty()) continue;
                const VoxelRegion& region = work->regions[level][r];
                vpush.regionMin = glm::ivec4(region.min, 0);
                vpush.regionMax = glm::ivec4(region.max, 0);
                for (uint32_t axis = 0; axis < 3; ++axis) {
                  vpush.axis = axis + 3 * level;
                  scissorToRegion(ctx, region, axis);
                  ctx.pushConstants(vpush);
                  in.scene.drawInstancesUnindexed(ctx, draw);
                }
              }
          })
          .add(graph);
    }

    // Mip m + 1 of the clipmap from mip m: the voxels for the first, the last mip for each next.
    for (uint32_t m = 0; m < mips; ++m) {
      ComputePass pass(in.device, fmt::format("legacy.voxel.mip{}", m + 1), "legacy/voxel_mip.comp");
      if (m == 0)
        pass.storageIn(shared::kLegacyBindingMipSrcRadiance, kVoxelRadiance)
            .storageOut(shared::kLegacyBindingRadianceMips, kVoxelRadianceMips, m);
      else
        pass.storageIn(shared::kLegacyBindingMipSrcRadiance, kVoxelRadianceMips, m - 1)
            .storageUpdate(shared::kLegacyBindingRadianceMips, kVoxelRadianceMips, m);
      pass.pipelineName("legacy.voxel.mips")
          .push(vpush)
          .record([vpush, work, m](graph::PassContext& ctx) { dispatchOverRegions(ctx, vpush, *work, m + 1); })
          .add(graph);
    }
  }

  // Rooms (shared/legacy.h): the finest level's voxels as solid, seeded or sealed air, then
  // `rounds` rounds of sweeps along x, y and z that flood the air from the seeds; the last
  // round counts what it still reaches (non-zero: not settled, the cones ignore the flood).
  // Each sweep is a pass: the graph orders them and places the barriers between them. Redone with the
  // voxels, over the whole level: the flood is global, and a 64^3 level costs a few sweeps.
  static void addRoomPasses(graph::RenderGraph& graph, FrameInputs& in, const shared::LegacyClipmap& clipmap,
                            uint32_t rounds) {
    const uint32_t R = clipmap.resolution;
    LegacyVoxelPush vpush{};
    vpush.clipmap = clipmap;
    ComputePass(in.device, "legacy.voxel.reach", "legacy/voxel_reach_init.comp")
        .storageIn(shared::kLegacyReachInitVoxels, kVoxelRadiance)
        .storageIn(shared::kLegacyBindingSeeds, kVoxelSeeds)
        .storageOut(shared::kLegacyBindingReach, kVoxelReach)
        .bufferOut(shared::kLegacyBindingReachUnsettled, kVoxelReachUnsettled)
        .push(vpush)
        .dispatch(R, R, R, 4, 4, 4)
        .add(graph);
    for (uint32_t sweep = 0; sweep < 3 * rounds; ++sweep) {
      vpush.axis = sweep % 3;
      vpush.level = sweep + 3 >= 3 * rounds ? 1u : 0u;  // the last round counts what it still reaches
      ComputePass(in.device, fmt::format("legacy.voxel.reach.sweep{}", sweep + 1), "legacy/voxel_reach_sweep.comp")
          .pipelineName("legacy.voxel.reach.sweep")
          .storageUpdate(shared::kLegacyBindingReach, kVoxelReach)
          .bufferUpdate(shared::kLegacyBindingReachUnsettled, kVoxelReachUnsettled)
          .push(vpush)
          .dispatch(R, R)
          .add(graph);
    }
  }

  // One voxelization round's pass: the list every round binds, the voxels as the next step.
  // Every binding but the frame, the voxels and the geometry is read only where the shader is
  // told it is there: the sun's map under kFrameFlagSunShadows, the light table when
  // lightCount > 0, the lights' maps through a light's shadowView, last frame's image when
  // screenRadiance (only with feedback). Absent, they are unbound: no stand-ins.
  // How a voxelization round binds the rooms' seeds: not at all (rooms off), as their first
  // writer this frame (a patch keeps what the seeds held), or as the next step after one.
  enum class SeedsAccess { Absent, Write, Update };
  static RasterPass voxelizePass(FrameInputs& in, const char* name, const LegacyVoxelPush& vpush, bool feedback,
                                 SeedsAccess seeds, uint32_t R) {
    const bool sun = (in.constants.flags & shared::kFrameFlagSunShadows) != 0;
    const bool mapped = in.lightShadowViews > 0;
    RasterPass pass(in.device, name, voxelizePipeline());
    pass.uniform(shared::kLegacyBindingFrame, kFrameConstants)
        .optionalSampled(shared::kLegacyBindingShadow, kShadowSunDepth, sun, samplers::sunShadowCompare)
        .storageUpdate(shared::kLegacyBindingRadiance, kVoxelRadiance)
        .bufferIn(shared::kLegacyBindingVertices, kSceneVertices)  // voxelize.vert fetches whole triangles
        .bufferIn(shared::kLegacyBindingIndices, kSceneIndices)
        .optionalBufferIn(shared::kBindingLights, kLightTable, in.constants.lightCount > 0)
        .optionalBufferIn(shared::kBindingLightShadowViews, kLightShadowViews, mapped)
        .optionalSampled(shared::kBindingLightShadowAtlas, kLightShadowAtlas, mapped, samplers::sunShadowCompare)
        .optionalSampled(shared::kBindingLightShadowDepth, kLightShadowAtlas, mapped, samplers::point)
        .optionalSampled(shared::kLegacyBindingPrevRadiance, kLegacyHistRadiance, feedback)
        .optionalSampled(shared::kLegacyBindingPrevDepth, kLegacyHistDepth, feedback)
        .drawsScene(in.scene.table(), true, Usage::StorageRead)
        .area(R, R)
        .push(vpush);
    if (seeds == SeedsAccess::Update)
      pass.storageUpdate(shared::kLegacyBindingSeeds, kVoxelSeeds);
    else
      pass.optionalStorageInOut(shared::kLegacyBindingSeeds, kVoxelSeeds, seeds == SeedsAccess::Write);
    return pass;
  }

  // Where the levels sit in the world, per level: the corner in whole voxels and the voxel
  // size (not camera-relative, so a camera moving within one voxel keeps them).
  static std::vector<glm::dvec4> voxelPlacement(const FrameInputs& in, const LegacyClipmapFit& fit) {
    std::vector<glm::dvec4> placement;
    for (uint32_t l = 0; l < fit.clipmap.levels; ++l) {
      const glm::dvec3 world = glm::dvec3(glm::vec3(fit.clipmap.levelMin[l])) + in.cameraWorld;
      const double v = fit.clipmap.levelMin[l].w;
      placement.emplace_back(glm::round(world / v), v);
    }
    return placement;
  }

  // The world boxes of the instances whose geometry changed since the last frame (where each
  // was and where it is): deformed meshes and moved instances. A deforming mesh's bounds hold
  // all its poses (scene::morphBounds), so they cover the old and the new pose alike.
  std::vector<scene::Bounds> takeInstanceChanges(const FrameInputs& in) {
    const auto& instances = in.sceneData.instances;
    std::vector<scene::Bounds> changes;
    const bool first = seen_.size() != instances.size();
    if (first) seen_.assign(instances.size(), {});
    for (size_t i = 0; i < instances.size(); ++i) {
      const uint64_t version = in.scene.meshVersion(in.scene.instanceMesh(i));
      Seen& was = seen_[i];
      if (!first && (was.meshVersion != version || was.transform != instances[i].transform)) {
        scene::Bounds box = was.bounds;
        box.extend(instances[i].worldBounds);
        changes.push_back(box);
      }
      was = {version, instances[i].transform, instances[i].worldBounds};
    }
    return changes;
  }

  // Keep, patch or rebuild. A new placement, sun or settings, or voxels lost (a reset, a
  // camera cut) rebuild, and rebuilds go on for a few frames while bounces through the screen
  // settle. A change of some instances patches the regions it reaches instead; with screen
  // feedback the settling rebuilds wait until the geometry stops changing, so an animation
  // never pays for whole rebuilds.
  VoxelWork planVoxelUpdate(const FrameInputs& in, const LegacyClipmapFit& fit, const std::vector<scene::Bounds>& changes,
                            bool placed, bool historyOk) {
    const RenderSettings& s = in.settings;
    const bool feedback = s.legacyScreenRadiance;
    if (!placed) settle_ = s.legacySettleFrames + 1;
    bool changed = !changes.empty();
    bool partial = placed && changed && s.legacyPartialVoxels && !s.legacyVoxelizeEveryFrame;
    VoxelWork work;
    if (partial) {
      work = partialWork(in, fit, changes);
      const double rebuildVoxels = double(fit.clipmap.levels) * std::pow(double(fit.clipmap.resolution), 3.0);
      if (work.regionCount() == 0)
        partial = changed = false;  // every change lies outside the clipmap: nothing in it changed
      else
        partial = double(work.regionVoxels) <= kPartialVoxelBudget * rebuildVoxels;
    }
    if (changed && (!partial || feedback)) settle_ = s.legacySettleFrames + 1;
    if (partial) return work;
    if (settle_ == 0 && !s.legacyVoxelizeEveryFrame) return {};
    // Bounces through the screen settle over a few rebuilds; only frames with history count.
    if (settle_ > 0 && (historyOk || !feedback)) --settle_;
    return fullWork(fit);
  }

  VoxelWork fullWork(const LegacyClipmapFit& fit) const {
    VoxelWork work;
    work.kind = VoxelWork::Kind::Full;
    const int r = int(fit.clipmap.resolution);
    for (uint32_t level = 0; level < fit.clipmap.levels; ++level) {
      work.regions.push_back({VoxelRegion{glm::ivec3(0), glm::ivec3(r)}});
      work.instances.push_back({allInstances_});
      work.regionVoxels += int64_t(r) * r * r;
    }
    work.instancesDrawn = uint32_t(allInstances_.size());
    return work;
  }

  // Per level, the voxels the changed boxes and their sun shadows reach, merged into a few
  // regions, and per region the instances whose bounds reach into it (changed or not: all
  // of them write there in a rebuild).
  VoxelWork partialWork(const FrameInputs& in, const LegacyClipmapFit& fit, const std::vector<scene::Bounds>& changes) const {
    const auto& c = in.constants;
    const bool shadows = (c.flags & shared::kFrameFlagSunShadows) != 0;
    // The voxelizer's 3x3 PCF of 2x2 comparisons reaches two texels, plus its normal offset and bias.
    const double margin = shadows ? double(c.shadowParams.x) * (3.0 + c.shadowParams.z) + c.shadowParams.y : 0.0;
    std::vector<scene::Bounds> reach;
    for (const scene::Bounds& box : changes)
      reach.push_back(shadows ? shadowSweptBounds(box, -glm::dvec3(glm::vec3(c.sunToLight)), in.sceneData.bounds, margin) : box);
    VoxelWork work;
    work.kind = VoxelWork::Kind::Partial;
    std::vector<bool> drawn(in.sceneData.instances.size(), false);
    for (uint32_t level = 0; level < fit.clipmap.levels; ++level) {
      std::vector<VoxelRegion> regions;
      for (const scene::Bounds& box : reach) regions.push_back(voxelRegionOf(fit.clipmap, level, in.cameraWorld, box));
      regions = mergeVoxelRegions(std::move(regions));
      std::vector<std::vector<uint32_t>> lists;
      const double slack = 0.5 * fit.clipmap.levelMin[level].w;  // against rounding at the region's faces
      for (const VoxelRegion& region : regions) {
        scene::Bounds world = worldBoundsOf(fit.clipmap, level, in.cameraWorld, region);
        std::vector<uint32_t> list;
        for (uint32_t i : allInstances_) {
          const scene::Bounds& b = in.sceneData.instances[i].worldBounds;
          if (glm::all(glm::lessThanEqual(b.min, world.max + slack)) && glm::all(glm::lessThanEqual(world.min - slack, b.max)))
            list.push_back(i), drawn[i] = true;
        }
        work.regionVoxels += region.voxels();
        lists.push_back(std::move(list));
      }
      work.regions.push_back(std::move(regions));
      work.instances.push_back(std::move(lists));
    }
    work.instancesDrawn = uint32_t(std::count(drawn.begin(), drawn.end(), true));
    return work;
  }

  void selectInstances(const std::vector<uint32_t>& from, DrawSet set, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t i : from)
      if (set == DrawSet::All || (set == DrawSet::Emissive) == bool(emissive_[i])) out.push_back(i);
  }

  // The raster covers the whole level; the scissor keeps it to the region's two axes on
  // screen (voxelize.vert swizzles x: yz, y: zx, z: xy).
  static void scissorToRegion(graph::PassContext& ctx, const VoxelRegion& region, uint32_t axis) {
    const int u = axis == 0 ? 1 : (axis == 1 ? 2 : 0), v = axis == 0 ? 2 : (axis == 1 ? 0 : 1);
    ctx.setScissor(uint32_t(region.min[u]), uint32_t(region.min[v]), uint32_t(region.max[u] - region.min[u]),
                   uint32_t(region.max[v] - region.min[v]));
  }

  // One compute dispatch over a box of one level's voxels, all six face blocks (4^3 groups).
  static void dispatchOverRegion(graph::PassContext& ctx, LegacyVoxelPush push, uint32_t level, const VoxelRegion& region) {
    push.level = level;
    push.regionMin = glm::ivec4(region.min, 0);
    push.regionMax = glm::ivec4(region.max, 0);
    ctx.pushConstants(push);
    const glm::ivec3 size = region.max - region.min;
    ctx.dispatch(6 * uint32_t(size.x), uint32_t(size.y), uint32_t(size.z), 4, 4, 4);
  }

  // The work's regions at clipmap mip `mip` (0: the voxels themselves): a patch's clear and
  // each mip. Footprints of two regions may share texels at coarse mips, which both write alike.
  static void dispatchOverRegions(graph::PassContext& ctx, const LegacyVoxelPush& push, const VoxelWork& work, uint32_t mip) {
    for (uint32_t level = 0; level < work.regions.size(); ++level)
      for (const VoxelRegion& region : work.regions[level])
        dispatchOverRegion(ctx, push, level, mip == 0 ? region : mipFootprint(region, mip));
  }

  // What the screen-space passes' shaders declare in legacy/legacy_common.glsl.
  static ComputePass withCommon(ComputePass pass) {
    pass.uniform(shared::kLegacyBindingFrame, kFrameConstants)
        .sampled(shared::kLegacyBindingDepth, gbuffer::kDepth)
        .sampled(shared::kLegacyBindingNormal, gbuffer::kNormal);
    return pass;
  }
  // What legacy/voxel_cones.glsl reads: the voxels, their mips and, with rooms, the flood.
  static ComputePass withVoxelCones(ComputePass pass, bool rooms) {
    pass.sampled(shared::kLegacyBindingRadiance, kVoxelRadiance, samplers::linear)
        .sampled(shared::kLegacyBindingRadianceMips, kVoxelRadianceMips, samplers::linear)
        .optionalSampled(shared::kLegacyBindingReach, kVoxelReach, rooms)
        .optionalBufferIn(shared::kLegacyBindingReachUnsettled, kVoxelReachUnsettled, rooms);
    return pass;
  }
  void prepare(FrameInputs& in) {
    if (sceneId_ == in.scene.id()) return;
    sceneId_ = in.scene.id();
    plainInstances_.clear();
    emissiveInstances_.clear();
    allInstances_.clear();
    emissive_.clear();
    seen_.clear();
    for (uint32_t i = 0; i < in.sceneData.instances.size(); ++i) {
      const auto& m = in.sceneData.materials[in.sceneData.meshes[in.sceneData.instances[i].mesh].material];
      const bool emits = glm::length(m.emissiveFactor) * m.emissiveStrength > 0.0f;
      (emits ? emissiveInstances_ : plainInstances_).push_back(i);
      allInstances_.push_back(i);
      emissive_.push_back(emits ? 1 : 0);
    }
  }

  // The voxelizing raster's shaders and state; its layout is the pass's list (RasterPass).
  static gpu::GraphicsPipelineDesc voxelizePipeline() {
    gpu::GraphicsPipelineDesc d;
    d.name = "legacy.voxelize";
    d.vertexShader = "legacy/voxelize.vert";
    d.fragmentShader = "legacy/voxelize.frag";
    // No vertex input: voxelize.vert fetches the vertices itself.
    d.cullMode = VK_CULL_MODE_NONE;
    d.depthTest = false;
    d.depthWrite = false;
    return d;
  }

  // What the voxels last saw of each instance.
  struct Seen {
    uint64_t meshVersion = 0;
    glm::dmat4 transform{1.0};
    scene::Bounds bounds;
  };
  // The last frame's voxel work, for figures().
  struct WorkFigures {
    VoxelWork::Kind kind = VoxelWork::Kind::Keep;
    uint32_t instancesDrawn = 0;
    int64_t regionVoxels = 0;
    uint32_t regions = 0;
  };

  std::optional<uint64_t> sceneId_;  // the scene prepare() last saw
  HistoryKeeper voxels_, screen_;
  std::vector<glm::dvec4> placement_;  // the voxels' placement in the last frame
  uint32_t settle_ = 0;
  std::vector<uint32_t> plainInstances_, emissiveInstances_, allInstances_;
  std::vector<uint8_t> emissive_;  // per instance
  std::vector<Seen> seen_;         // per instance
  WorkFigures lastWork_;
};

}  // namespace

LegacyClipmapFit fitLegacyClipmap(const scene::Bounds& bounds, const glm::dvec3& camera, uint32_t resolution,
                                  float level0Extent, uint32_t maxLevels) {
  LegacyClipmapFit fit;
  uint32_t R = 16;
  while (R < resolution && R < 256) R *= 2;
  const glm::dvec3 size = bounds.valid() ? bounds.size() : glm::dvec3(1.0);
  const double maxAxis = std::max({size.x, size.y, size.z, 1e-3}) * 1.02;  // a margin so walls on the bounds are inside
  // Unset: the finest level holds the scene (the automatic value, render_settings.cpp).
  const double e0 = level0Extent > 0.0f ? double(level0Extent) : maxAxis;
  const uint32_t levels =
      // A finest level within 1e-4 of the scene's side holds it (the automatic value arrives
      // through a float, and rounding must not add a level at one scale and not at another).
      std::clamp(1u + uint32_t(std::max(0.0, std::ceil(std::log2(maxAxis / e0) - 1e-4))), 1u, std::min(maxLevels, shared::kLegacyMaxLevels));
  const glm::dvec3 centreOfScene = bounds.valid() ? bounds.center() : glm::dvec3(0.0);
  // Voxel faces sit half a voxel off the scene's centre (and off the world's origin): authored
  // geometry lies on them otherwise (a wall through the middle of a symmetric scene, a floor at
  // y = 0), and a surface exactly on a face falls into the voxel on one side or the other by the
  // rounding of its position, which differs with the scene's scale.
  for (uint32_t l = 0; l < levels; ++l) {
    const double voxel = e0 / R * std::exp2(double(l)), extent = voxel * R;
    glm::dvec3 centre;
    for (int a = 0; a < 3; ++a) {
      if (extent >= size[a] * 1.02 * (1.0 - 1e-4)) {  // (with the levels' count's tolerance)
        // The level spans the scene on this axis (no need to follow the camera); the half-voxel
        // shift stays within the margin, so walls on the bounds stay inside.
        centre[a] = centreOfScene[a] + std::min(0.5 * voxel, 0.45 * (extent - size[a]));
      } else {
        double c = (std::floor(camera[a] / voxel) + 0.5) * voxel;  // half a voxel off the grid: stable as the camera moves
        double lo = bounds.min[a] + 0.5 * extent - voxel, hi = bounds.max[a] - 0.5 * extent + voxel;
        centre[a] = std::clamp(c, lo, std::max(lo, hi));
      }
    }
    glm::dvec3 minCorner = centre - 0.5 * extent - camera;
    fit.clipmap.levelMin[l] = glm::vec4(glm::vec3(minCorner), float(voxel));
  }
  fit.clipmap.resolution = R;
  fit.clipmap.levels = levels;
  uint32_t mips = 0;
  for (uint32_t r = R / 2; r >= 1; r /= 2) ++mips;
  fit.clipmap.mipCount = mips;
  return fit;
}

std::unique_ptr<LightingPath> makeLegacyPath() { return std::make_unique<LegacyPath>(); }

}  // namespace tl::lighting
