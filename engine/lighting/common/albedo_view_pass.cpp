#include "lighting/common/albedo_view_pass.h"

#include "graph/executor.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/copy_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"
#include "shared/albedo.h"

namespace tl::lighting {

void AlbedoViewPass::add(graph::RenderGraph& graph, FrameInputs& in) {
  if (!in.instanceAlbedo) return;
  const uint32_t w = in.settings.width, h = in.settings.height;
  // The resolved table, uploaded when it changed (a copy per frame in flight).
  const std::vector<glm::vec4>& table = *in.instanceAlbedo;
  const VkDeviceSize bytes = std::max<size_t>(1, table.size()) * sizeof(glm::vec4);
  const uint64_t frame = in.frame;
  if (!perInstance_ || perInstance_.size() < bytes || uploadedVersion_ != in.instanceAlbedoVersion ||
      sceneId_ != in.scene.id()) {
    if (!perInstance_ || perInstance_.size() < bytes)
      perInstance_ = gpu::UploadRing(in.device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, kAlbedoPerInstance);
    if (!table.empty()) perInstance_.write(frame, table.data(), table.size() * sizeof(glm::vec4));
    uploadedVersion_ = in.instanceAlbedoVersion;
    if (sceneId_ != in.scene.id()) haveBaseline_ = false;
    sceneId_ = in.scene.id();
  }
  graph.importBuffer(kAlbedoPerInstance, graph::ResourceDesc::buffer(perInstance_.size(), "per instance: resolved albedo (rgb), source (w)"), perInstance_.forFrame(frame));

  ComputePass(in.device, "albedo.view", "common/albedo_view.comp")
      .sampled(shared::kAlbedoViewBindingInstanceId, gbuffer::kInstanceId)
      .sampled(shared::kAlbedoViewBindingBaseColor, gbuffer::kBaseColor)
      .sampled(shared::kAlbedoViewBindingMaterial, gbuffer::kMaterial)
      .bufferIn(shared::kAlbedoViewBindingPerInstance, kAlbedoPerInstance)
      .storageOut(shared::kAlbedoViewBindingInstance, kAlbedoInstance,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "albedo the RT rays read (rgb); a: 1 override, 2 baked, 3 texture average")
                      .decodedAs("albedo-source"))
      .storageOut(shared::kAlbedoViewBindingDifference, kAlbedoDifference,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "|database albedo - G-buffer hit albedo| (rgb), signed luminance (a)"))
      .dispatch(w, h)
      .add(graph);

  // The baseline is a cache: written from the final image in the frame that captures it,
  // kept unchanged after.
  graph.declareCache(kAlbedoImpactBaseline, in.screenImage(kCompositeHdrFormat, "final image before the albedo edits"));
  if (captureBaseline_) {
    addCopyPass(graph, "albedo.impactBaseline", {{kCompositeHdr, kAlbedoImpactBaseline}});
    captureBaseline_ = false;
    haveBaseline_ = true;
  }
  if (!haveBaseline_) return;
  ComputePass(in.device, "albedo.impact", "common/albedo_impact.comp")
      .sampled(shared::kAlbedoViewBindingCurrent, kCompositeHdr)
      .sampled(shared::kAlbedoViewBindingBaseline, kAlbedoImpactBaseline)
      .storageOut(shared::kAlbedoViewBindingImpact, kAlbedoImpact,
                  in.screenImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                 "|final image - before the albedo edits| (rgb), signed luminance (a)"))
      .dispatch(w, h)
      .add(graph);
}

}  // namespace tl::lighting
