#include "lighting/common/lights_pass.h"

#include "graph/executor.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/light_shadows.h"
#include "lighting/common/light_table.h"
#include "shared/brdf_lut.h"
#include "shared/lights.h"

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

}  // namespace tl::lighting
