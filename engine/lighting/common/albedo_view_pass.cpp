#include "lighting/common/albedo_view_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "shared/albedo.h"

namespace tl::lighting {

void AlbedoViewPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  if (!in.instanceAlbedo) return;
  const uint32_t w = in.settings.width, h = in.settings.height;
  if (!view_) {
    point_ = gpu::Sampler(in.device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "albedo.point");
    const auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    gpu::ComputePipelineDesc v;
    v.name = "albedo.view";
    v.shader = "common/albedo_view.comp";
    v.layout.bindings = {{shared::kAlbedoViewBindingInstanceId, sampled}, {shared::kAlbedoViewBindingBaseColor, sampled},
                         {shared::kAlbedoViewBindingMaterial, sampled},
                         {shared::kAlbedoViewBindingPerInstance, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                         {shared::kAlbedoViewBindingInstance, storage}, {shared::kAlbedoViewBindingDifference, storage}};
    view_ = gpu::createComputePipeline(in.device, v);
    gpu::ComputePipelineDesc i;
    i.name = "albedo.impact";
    i.shader = "common/albedo_impact.comp";
    i.layout.bindings = {{shared::kAlbedoViewBindingCurrent, sampled}, {shared::kAlbedoViewBindingBaseline, sampled},
                         {shared::kAlbedoViewBindingImpact, storage}};
    impact_ = gpu::createComputePipeline(in.device, i);
  }

  // The resolved table, uploaded when it changed (the executor waits for each frame).
  const std::vector<glm::vec4>& table = *in.instanceAlbedo;
  const VkDeviceSize bytes = std::max<size_t>(1, table.size()) * sizeof(glm::vec4);
  if (!perInstance_ || perInstance_.size() < bytes || uploadedVersion_ != in.instanceAlbedoVersion ||
      sceneId_ != in.scene.id()) {
    if (!perInstance_ || perInstance_.size() < bytes)
      perInstance_ = gpu::Buffer(in.device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                 kAlbedoPerInstance);
    if (!table.empty()) perInstance_.write(table.data(), table.size() * sizeof(glm::vec4));
    uploadedVersion_ = in.instanceAlbedoVersion;
    if (sceneId_ != in.scene.id()) haveBaseline_ = false;
    sceneId_ = in.scene.id();
  }
  graph.declareImported(kAlbedoPerInstance,
                        graph::ResourceDesc::buffer(perInstance_.size(), "per instance: resolved albedo (rgb), source (w)"));
  in.executor.bindImportedBuffer(kAlbedoPerInstance, perInstance_);

  constexpr VkImageLayout kReadOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  graph.addPass(
      "albedo.view", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        for (const char* n : {"gbuffer.instanceId", "gbuffer.baseColor", "gbuffer.material"}) b.read(n, graph::Usage::Sampled);
        b.read(kAlbedoPerInstance, graph::Usage::StorageRead);
        b.create(kAlbedoInstance,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              "albedo the RT rays read (rgb); a: 1 override, 2 baked, 3 texture average")
                     .decodedAs("albedo-source"),
                 graph::Usage::StorageWrite);
        b.create(kAlbedoDifference,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              "|database albedo - G-buffer hit albedo| (rgb), signed luminance (a)"),
                 graph::Usage::StorageWrite);
      },
      [this](graph::PassContext& ctx) {
        ctx.bind(view_);
        ctx.descriptors()
            .sampledImage(shared::kAlbedoViewBindingInstanceId, ctx.image("gbuffer.instanceId").view(), point_.handle(), kReadOnly)
            .sampledImage(shared::kAlbedoViewBindingBaseColor, ctx.image("gbuffer.baseColor").view(), point_.handle(), kReadOnly)
            .sampledImage(shared::kAlbedoViewBindingMaterial, ctx.image("gbuffer.material").view(), point_.handle(), kReadOnly)
            .storageBuffer(shared::kAlbedoViewBindingPerInstance, ctx.buffer(kAlbedoPerInstance).handle())
            .storageImage(shared::kAlbedoViewBindingInstance, ctx.image(kAlbedoInstance).view())
            .storageImage(shared::kAlbedoViewBindingDifference, ctx.image(kAlbedoDifference).view());
        VkExtent3D e = ctx.extent(kAlbedoInstance);
        ctx.dispatch(e.width, e.height);
      });

  // The baseline is a cache: written from the final image in the frame that captures it,
  // kept unchanged after.
  graph.declareCache(kAlbedoImpactBaseline,
                     graph::ResourceDesc::image2D(kCompositeHdrFormat, w, h, "final image before the albedo edits"));
  if (captureBaseline_) {
    addCopyPass(graph, "albedo.impactBaseline", {{kCompositeHdr, kAlbedoImpactBaseline}});
    captureBaseline_ = false;
    haveBaseline_ = true;
  }
  if (!haveBaseline_) return;
  graph.addPass(
      "albedo.impact", graph::PassKind::Compute,
      [&](graph::PassBuilder& b) {
        b.read(kCompositeHdr, graph::Usage::Sampled);
        b.read(kAlbedoImpactBaseline, graph::Usage::Sampled);
        b.create(kAlbedoImpact,
                 graph::ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, w, h,
                                              "|final image - before the albedo edits| (rgb), signed luminance (a)"),
                 graph::Usage::StorageWrite);
      },
      [this](graph::PassContext& ctx) {
        ctx.bind(impact_);
        ctx.descriptors()
            .sampledImage(shared::kAlbedoViewBindingCurrent, ctx.image(kCompositeHdr).view(), point_.handle(), kReadOnly)
            .sampledImage(shared::kAlbedoViewBindingBaseline, ctx.image(kAlbedoImpactBaseline).view(), point_.handle(), kReadOnly)
            .storageImage(shared::kAlbedoViewBindingImpact, ctx.image(kAlbedoImpact).view());
        VkExtent3D e = ctx.extent(kAlbedoImpact);
        ctx.dispatch(e.width, e.height);
      });
}

}  // namespace tl::lighting
