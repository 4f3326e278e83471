#include "lighting/common/lights_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/light_table.h"
#include "lighting/common/redeferred_pass.h"
#include "shared/brdf_lut.h"
#include "shared/lights.h"
#include "shared/redeferred.h"

namespace tl::lighting {

using graph::Usage;

namespace {
constexpr const char* kStandIn = "lights.accum.none";
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
  if (in.settings.redeferred) return addIbuffer(graph, in, structures, tlasHandle);
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  gpu::Pipeline& pipeline = traced ? traced_ : unshadowed_;
  if (!pipeline) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = traced ? "lights.direct.traced" : "lights.direct";
    d.shader = traced ? "common/lights_traced.comp" : "common/lights.comp";
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
    d.layout.pushConstantBytes = sizeof(shared::LightsPush);
    pipeline = gpu::createComputePipeline(in.device, d);
  }
  if (point_.handle() == VK_NULL_HANDLE) point_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.point");
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
        if (push.accumulate)
          b.write(accum, Usage::StorageWrite);
        else  // the binding still needs an rgba32f storage image: one texel, never written
          b.create(kStandIn, graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1, "unused accumulation binding"),
                   Usage::StorageWrite);
        b.create(kLightsRadiance,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              traced ? "radiance from the light table, ray-traced shadows"
                                                     : "radiance from the light table, unshadowed"),
                 Usage::StorageWrite);
      },
      [this, &in, &pipeline, traced, tlasHandle, push, accum](graph::PassContext& ctx) {
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
        d.storageImage(shared::kLightsPassAccum, ctx.image(push.accumulate ? accum : std::string(kStandIn)).view());
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  return kLightsRadiance;
}

// The same picks and shadow rays, summed into the I-buffer's four sums of light instead of
// radiance (shaders/common/ibuffer_lights.glsl), each accumulated like the radiance.
std::string LightsPass::addIbuffer(graph::RenderGraph& graph, FrameInputs& in, const std::vector<std::string>& structures,
                                   VkAccelerationStructureKHR tlasHandle) {
  constexpr uint32_t kOut[4] = {shared::kIbufferOutDg, shared::kIbufferOutSg1, shared::kIbufferOutSg2, shared::kIbufferOutMs};
  constexpr uint32_t kAccum[4] = {shared::kIbufferAccumDg, shared::kIbufferAccumSg1, shared::kIbufferAccumSg2,
                                  shared::kIbufferAccumMs};
  const bool traced = !structures.empty() && tlasHandle != VK_NULL_HANDLE;
  gpu::Pipeline& pipeline = traced ? ibufferTraced_ : ibufferUnshadowed_;
  if (!pipeline) {
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    gpu::ComputePipelineDesc d;
    d.name = traced ? "lights.ibuffer.traced" : "lights.ibuffer";
    d.shader = traced ? "common/ibuffer_lights_traced.comp" : "common/ibuffer_lights.comp";
    d.layout.bindings = {{shared::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                         {shared::kLightsPassNormal, sampled},
                         {shared::kLightsPassMaterial, sampled},
                         {shared::kLightsPassDepth, sampled},
                         {shared::kBindingBrdfTables, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    for (uint32_t b : kOut) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    for (uint32_t b : kAccum) d.layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    if (traced) d.layout.bindings.push_back({shared::kLightsPassTlas, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
    d.layout.pushConstantBytes = sizeof(shared::LightsPush);
    pipeline = gpu::createComputePipeline(in.device, d);
  }
  if (point_.handle() == VK_NULL_HANDLE) point_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "lights.point");
  const uint32_t w = in.settings.width, h = in.settings.height;
  shared::LightsPush push{};
  std::array<std::string, 4> accum;
  // lights.accum.<path>.Ldg ...: the suffix of ibuffer.Ldg ...
  for (size_t q = 0; q < accum.size(); ++q)
    accum[q] = "lights.accum." + in.pathName + std::string(kIbuffer[q]).substr(std::string_view("ibuffer").size());
  const auto accumDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                      "sum of estimates of an I-buffer sum of light (rgb) and their count (a)");
  const std::string keeper = in.pathName + ".ibuffer";
  if (in.constants.lightCount > shared::kLightsLoopMax) {
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
  graph.addPass(
      "lights.direct", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kFrameConstants, Usage::StorageRead);
        b.read(kBrdfTables, Usage::StorageRead);
        b.read(kLightTable, Usage::StorageRead);
        for (const char* n : {"gbuffer.normal", "gbuffer.material"}) b.read(n, Usage::Sampled);
        b.read(kGbufferDepth, Usage::Sampled);
        if (traced)
          for (const auto& s : structures) b.read(s, Usage::AccelerationStructureRead);
        if (push.accumulate)
          for (const auto& a : accum) b.write(a, Usage::StorageWrite);
        else  // the bindings still need an rgba32f storage image: one texel, never written
          b.create(kStandIn, graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1, "unused accumulation binding"),
                   Usage::StorageWrite);
        for (size_t q = 0; q < kLightsIbuffer.size(); ++q)
          b.create(kLightsIbuffer[q],
                   graph::ResourceDesc::image2D(VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                                std::string("the light table's share of ") + kIbuffer[q] + ", " +
                                                    (traced ? "ray-traced shadows" : "unshadowed"))
                       .decodedAs(ibufferDecoder(q)),
                   Usage::StorageWrite);
      },
      [this, &in, &pipeline, traced, tlasHandle, push, accum, kOut, kAccum](graph::PassContext& ctx) {
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
        for (size_t q = 0; q < 4; ++q) {
          d.storageImage(kOut[q], ctx.image(kLightsIbuffer[q]).view());
          d.storageImage(kAccum[q], ctx.image(push.accumulate ? accum[q] : std::string(kStandIn)).view());
        }
        ctx.pushConstants(push);
        ctx.dispatch(in.settings.width, in.settings.height);
      });
  return kLightsIbuffer[0];
}

}  // namespace tl::lighting
