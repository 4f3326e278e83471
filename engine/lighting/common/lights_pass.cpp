#include "lighting/common/lights_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/light_shadows.h"
#include "lighting/common/light_table.h"
#include "lighting/common/redeferred_pass.h"
#include "shared/brdf_lut.h"
#include "shared/lights.h"
#include "shared/redeferred.h"

namespace tl::lighting {

using graph::Usage;

namespace {
constexpr const char* kStandIn = "lights.accum.none";
constexpr const char* kRefineStandIn = "lights.accum.none.refine";
constexpr HistoryPolicy kLightsAccumulation{
    "lights.accumulation",
    parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection, FramePart::Sun,
          FramePart::Scene, FramePart::Geometry, FramePart::Settings),
    0};
}  // namespace

VkBuffer lightTableOrStandIn(graph::PassContext& ctx, const FrameInputs& in, VkBuffer standIn) {
  return in.constants.lightCount > 0 ? ctx.buffer(kLightTable).handle() : standIn;
}

std::string LightsPass::add(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                            VkAccelerationStructureKHR tlasHandle) {
  if (in.constants.lightCount == 0) return "";
  if (in.settings.redeferred)
    return addIbuffer(graph, in, structures, tlasHandle,
                      shared::tlIbufferPattern(in.settings.redeferredRate) == shared::kIbufferPatternEvery
                          ? shared::kIbufferStageEvery
                          : shared::kIbufferStagePattern);
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  const bool mapped = !traced && in.lightShadowViews > 0;
  gpu::Pipeline& pipeline = traced ? traced_ : (mapped ? shadowed_ : unshadowed_);
  if (!pipeline) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = traced ? "lights.direct.traced" : (mapped ? "lights.direct.mapped" : "lights.direct");
    d.shader = traced ? "common/lights_traced.comp" : (mapped ? "common/lights_shadowed.comp" : "common/lights.comp");
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kLightsPassBaseColor, sampled},
                         {shared::kLightsPassNormal, sampled},
                         {shared::kLightsPassMaterial, sampled},
                         {shared::kLightsPassDepth, sampled},
                         {shared::kLightsPassOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    d.layout.bindings.push_back({shared::kLightsPassAccum, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    if (traced) d.layout.bindings.push_back({shared::kLightsPassTlas, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
    if (mapped) {
      d.layout.bindings.push_back({shared::kBindingLightShadowViews, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
      d.layout.bindings.push_back({shared::kBindingLightShadowAtlas, sampled});
    }
    d.layout.pushConstantBytes = sizeof(shared::LightsPush);
    pipeline = gpu::createComputePipeline(in.device, d);
  }
  if (point_.handle() == VK_NULL_HANDLE) point_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.point");
  if (mapped && shadowCompare_.handle() == VK_NULL_HANDLE)
    shadowCompare_ = gpu::Sampler(in.device, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.shadowCompare", true);
  const uint32_t w = in.settings.width, h = in.settings.height;
  // Many lights: a noisy estimate, accumulated while nothing it depends on changes.
  shared::LightsPush push{};
  const std::string accum = "lights.accum." + in.pathName;
  const auto accumDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                      "sum of light-table estimates (rgb) and their count (a)");
  if (in.constants.lightCount > shared::kLightsLoopMax) {
    push.accumulate = 1;
    const bool stored = in.executor.historyValid(accum, accumDesc);
    push.restart = accumulation_[in.pathName].advance(kLightsAccumulation, in.key, in.pathName, in.historyLog, {stored})
                               .action == HistoryAction::Restart
                       ? 1u
                       : 0u;
    graph.declarePersistent(accum, accumDesc);
  } else {
    accumulation_.erase(in.pathName);
  }
  graph.addPass(
      "lights.direct", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        b.read(kLightTable, Usage::StorageRead);
        for (const char* n : {"gbuffer.baseColor", "gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (traced)
          for (const auto& s : structures) b.read(s, Usage::AccelerationStructureRead);
        if (mapped) {
          b.read(kLightShadowViews, Usage::StorageRead);
          b.read(kLightShadowAtlas, Usage::Sampled);
        }
        if (push.accumulate)
          b.write(accum, Usage::StorageWrite);
        else  // the binding still needs an rgba32f storage image: one texel, never written
          b.create(kStandIn, graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1, "unused accumulation binding"),
                   Usage::StorageWrite);
        b.create(kLightsRadiance,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              traced   ? "radiance from the light table, ray-traced shadows"
                                              : mapped ? "radiance from the light table, shadow-mapped point and spot lights"
                                                       : "radiance from the light table, unshadowed"),
                 Usage::StorageWrite);
      },
      [this, &in, &pipeline, traced, mapped, tlasHandle, push, accum](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        VkSampler pt = point_.handle();
        ctx.bind(pipeline);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kLightsPassBaseColor, ctx.image("gbuffer.baseColor").view(), pt, ro)
                      .sampledImage(shared::kLightsPassNormal, ctx.image("gbuffer.normal").view(), pt, ro)
                      .sampledImage(shared::kLightsPassMaterial, ctx.image("gbuffer.material").view(), pt, ro)
                      .sampledImage(shared::kLightsPassDepth, ctx.image(kGbufferDepth).view(), pt, ro)
                      .storageImage(shared::kLightsPassOutput, ctx.image(kLightsRadiance).view())
                      .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle())
                      .storageBuffer(shared::kBindingLights, ctx.buffer(kLightTable).handle());
        if (traced) d.accelerationStructure(shared::kLightsPassTlas, tlasHandle);
        if (mapped)
          d.storageBuffer(shared::kBindingLightShadowViews, ctx.buffer(kLightShadowViews).handle())
              .sampledImage(shared::kBindingLightShadowAtlas, ctx.image(kLightShadowAtlas).view(), shadowCompare_.handle(), ro);
        d.storageImage(shared::kLightsPassAccum, ctx.image(push.accumulate ? accum : std::string(kStandIn)).view());
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  return kLightsRadiance;
}

// The same picks and shadow rays, summed into the I-buffer's four sums of light instead of
// radiance (shaders/common/ibuffer_lights.glsl), each accumulated like the radiance.
void LightsPass::addIbufferRefine(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                                  VkAccelerationStructureKHR tlasHandle) {
  addIbuffer(graph, in, structures, tlasHandle, shared::kIbufferStageRefine);
}

std::string LightsPass::addIbuffer(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                                   VkAccelerationStructureKHR tlasHandle, uint32_t stage) {
  constexpr uint32_t kOut[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2, shared::kIbufferOutMs};
  constexpr uint32_t kAccum[4] = {shared::kIbufferAccumDg, shared::kIbufferAccumSg1, shared::kIbufferAccumSg2,
                                  shared::kIbufferAccumMs};
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  const bool mapped = !traced && in.lightShadowViews > 0;
  gpu::Pipeline& pipeline = traced ? ibufferTraced_ : (mapped ? ibufferShadowed_ : ibufferUnshadowed_);
  if (!pipeline) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = traced ? "lights.ibuffer.traced" : (mapped ? "lights.ibuffer.mapped" : "lights.ibuffer");
    d.shader = traced ? "common/ibuffer_lights_traced.comp"
                      : (mapped ? "common/ibuffer_lights_shadowed.comp" : "common/ibuffer_lights.comp");
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kLightsPassNormal, sampled},
                         {shared::kLightsPassMaterial, sampled},
                         {shared::kLightsPassDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    for (uint32_t b : kOut) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    for (uint32_t b : kAccum) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    d.layout.bindings.push_back({shared::kIbufferRefineMaskSampled, sampled});
    if (traced) d.layout.bindings.push_back({shared::kLightsPassTlas, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
    if (mapped) {
      d.layout.bindings.push_back({shared::kBindingLightShadowViews, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
      d.layout.bindings.push_back({shared::kBindingLightShadowAtlas, sampled});
    }
    d.layout.pushConstantBytes = sizeof(shared::LightsPush);
    pipeline = gpu::createComputePipeline(in.device, d);
  }
  if (point_.handle() == VK_NULL_HANDLE) point_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.point");
  if (mapped && shadowCompare_.handle() == VK_NULL_HANDLE)
    shadowCompare_ = gpu::Sampler(in.device, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.shadowCompare", true);
  const uint32_t w = in.settings.width, h = in.settings.height;
  const uint32_t pattern = shared::tlIbufferPattern(in.settings.redeferredRate);
  const bool refine = stage == shared::kIbufferStageRefine;
  shared::LightsPush push{};
  std::array<std::string, 4> accum;
  // lights.accum.<path>.Ldg ...: the suffix of ibuffer.Ldg ...
  // The refining run keeps its own sums (one writer per image): lights.accum.<path>.refine.Ldg ...
  for (size_t q = 0; q < accum.size(); ++q)
    accum[q] = "lights.accum." + in.pathName + (refine ? ".refine" : "") +
               std::string(kIbuffer[q]).substr(std::string_view("ibuffer").size());
  const auto& outputs = refine ? kLightsRefined : kLightsIbuffer;
  const char* standIn = refine ? kRefineStandIn : kStandIn;
  const auto accumDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                      "sum of estimates of an I-buffer sum of light (rgb) and their count (a)");
  // One sum per pattern: another pattern's sums hold other pixels' estimates.
  const std::string keeper = in.pathName + ".ibuffer." + std::to_string(pattern);
  for (uint32_t other = shared::kIbufferPatternEvery; other <= shared::kIbufferPatternBlocks; ++other)
    if (other != pattern) accumulation_.erase(in.pathName + ".ibuffer." + std::to_string(other));
  if (refine) {
    push = ibufferPush_;  // the same sums, restarted or not, as this frame's pattern run
    if (push.accumulate) {
      bool stored = true;
      for (const auto& a : accum) stored = stored && in.executor.historyValid(a, accumDesc);
      if (!stored) push.restart = 1;  // its images are new: nothing to add to
      for (const auto& a : accum) graph.declarePersistent(a, accumDesc);
    }
  } else if (in.constants.lightCount > shared::kLightsLoopMax) {
    push.accumulate = 1;
    bool stored = true;
    for (const auto& a : accum) stored = stored && in.executor.historyValid(a, accumDesc);
    push.restart = accumulation_[keeper].advance(kLightsAccumulation, in.key, in.pathName, in.historyLog, {stored}).action ==
                           HistoryAction::Restart
                       ? 1u
                       : 0u;
    for (const auto& a : accum) graph.declarePersistent(a, accumDesc);
  } else {
    accumulation_.erase(keeper);
  }
  push.ibufferStage = stage;
  push.ibufferPattern = pattern;
  if (!refine) ibufferPush_ = push;
  graph.addPass(
      refine ? "lights.direct.refine" : "lights.direct", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        b.read(kLightTable, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (traced)
          for (const auto& s : structures) b.read(s, Usage::AccelerationStructureRead);
        if (mapped) {
          b.read(kLightShadowViews, Usage::StorageRead);
          b.read(kLightShadowAtlas, Usage::Sampled);
        }
        if (refine) b.read(kIbufferRefine, Usage::Sampled);
        if (push.accumulate)
          for (const auto& a : accum) b.write(a, Usage::StorageWrite);
        else  // the bindings still need an rgba32f storage image: one texel, never written
          b.create(standIn, graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1, "unused accumulation binding"),
                   Usage::StorageWrite);
        for (size_t q = 0; q < kLightsIbuffer.size(); ++q)
          b.create(outputs[q],
                   graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                std::string("the light table's share of ") + kIbuffer[q] + ", " +
                                                    (traced   ? "ray-traced shadows"
                                                     : mapped ? "shadow-mapped point and spot lights"
                                                              : "unshadowed"))
                       .decodedAs(ibufferDecoder(q)),
                   Usage::StorageWrite);
      },
      [this, &in, &pipeline, traced, mapped, refine, &outputs, standIn, tlasHandle, push, accum, kOut, kAccum](graph::PassContext& ctx) {
        const VkImageLayout ro = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
        VkSampler pt = point_.handle();
        ctx.bind(pipeline);
        auto& d = ctx.descriptors()
                      .uniformBuffer(shared::kBindingFrame, in.constantsBuffer.handle())
                      .sampledImage(shared::kLightsPassNormal, ctx.image("gbuffer.normal").view(), pt, ro)
                      .sampledImage(shared::kLightsPassMaterial, ctx.image("gbuffer.material").view(), pt, ro)
                      .sampledImage(shared::kLightsPassDepth, ctx.image(kGbufferDepth).view(), pt, ro)
                      .storageBuffer(shared::kBindingBrdfTables, ctx.buffer(kBrdfTables).handle())
                      .storageBuffer(shared::kBindingLights, ctx.buffer(kLightTable).handle());
        if (traced) d.accelerationStructure(shared::kLightsPassTlas, tlasHandle);
        if (mapped)
          d.storageBuffer(shared::kBindingLightShadowViews, ctx.buffer(kLightShadowViews).handle())
              .sampledImage(shared::kBindingLightShadowAtlas, ctx.image(kLightShadowAtlas).view(), shadowCompare_.handle(), ro);
        for (size_t q = 0; q < 4; ++q) {
          d.storageImage(kOut[q], ctx.image(outputs[q]).view());
          d.storageImage(kAccum[q], ctx.image(push.accumulate ? accum[q] : std::string(standIn)).view());
        }
        // Outside the refining run the mask's binding holds the depth, unread.
        d.sampledImage(shared::kIbufferRefineMaskSampled, ctx.image(refine ? kIbufferRefine : kGbufferDepth).view(), pt, ro);
        ctx.pushConstants(push);
        const glm::uvec2 grid = push.ibufferStage == shared::kIbufferStagePattern
                                    ? shared::tlIbufferPatternGrid(glm::uvec2(in.settings.width, in.settings.height), push.ibufferPattern)
                                    : glm::uvec2(in.settings.width, in.settings.height);
        ctx.dispatch(grid.x, grid.y);
      });
  return kLightsIbuffer[0];
}

}  // namespace tl::lighting
