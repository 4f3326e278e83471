#include "session/frame_pipeline.h"

#include "lighting/common/albedo_view_pass.h"
#include "lighting/common/compare_view_pass.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/environment_table.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/light_shadow_pass.h"
#include "lighting/common/light_table.h"
#include "lighting/common/lights_pass.h"
#include "lighting/common/shadow_pass.h"
#include "lighting/common/taa_pass.h"
#include "shared/brdf_tables.h"

#include <algorithm>

namespace tl::session {

struct FramePipeline::Passes {
  lighting::GbufferPass gbuffer;
  lighting::ShadowPass shadow;
  lighting::LightShadowPass lightShadow;
  lighting::LightsPass lights;
  lighting::CompositePass composite;
  lighting::TaaPass taa;
  lighting::TonemapPass tonemap;
  lighting::DisplayPass display;
  lighting::AlbedoViewPass albedoView;
  lighting::CompareViewPass compareView;
};

FramePipeline::FramePipeline(gpu::Device& device) : device_(device), passes_(std::make_unique<Passes>()) {
  constants_ = gpu::UploadRing(device_, sizeof(shared::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               lighting::kFrameConstants);
  brdfTables_ = gpu::Buffer(device_, sizeof(shared::BrdfTables), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            gpu::MemoryUsage::Upload, lighting::kBrdfTables);
  brdfTables_.write(&shared::kBrdfTables, sizeof(shared::BrdfTables));
}

FramePipeline::~FramePipeline() = default;

void FramePipeline::resetPasses() { passes_ = std::make_unique<Passes>(); }

lighting::AlbedoViewPass& FramePipeline::albedoView() { return passes_->albedoView; }

void FramePipeline::uploadEnvironmentTable(const scene::EnvironmentMap& map) {
  if (environmentTableHash_ == map.contentHash && environmentTable_.size() != 0) return;
  const std::vector<float> table = scene::environmentTable(map);
  device_.waitIdle();  // an earlier frame may still read the table being replaced
  environmentTable_ = gpu::Buffer(device_, table.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  gpu::MemoryUsage::Upload, lighting::kEnvironmentTable);
  environmentTable_.write(table.data(), table.size() * sizeof(float));
  environmentTableHash_ = map.contentHash;
}

FrameLights FramePipeline::importBuffers(graph::RenderGraph& graph, uint64_t frame, shared::FrameConstants& fc,
                                         scene::GpuScene& gpuScene, const std::vector<scene::Light>& sceneLights,
                                         const scene::EnvironmentMap* environmentMap, const scene::Bounds& bounds,
                                         const glm::dvec3& camera, const lighting::RenderSettings& settings) {
  // The light table exists only in frames that have lights to shade: without, no pass reads it.
  FrameLights out;
  out.lights = lighting::buildLightTable(sceneLights, camera, fc.sceneScale);
  fc.lightCount = uint32_t(out.lights.size());
  constants_.write(frame, &fc, sizeof(fc));
  graph.importBuffer(lighting::kFrameConstants, graph::ResourceDesc::buffer(constants_.size(), "per-frame constants (shared/frame.h)"), constants_.forFrame(frame));
  graph.importBuffer(lighting::kBrdfTables, graph::ResourceDesc::buffer(brdfTables_.size(), "the shared BRDF's tables (shared/brdf_lut.h)"), brdfTables_);
  gpuScene.importBuffers(graph, frame);
  // Point, spot and area lights' shadow maps (direct, legacy): their views exist only with such lights.
  const glm::dvec3 relMin = bounds.valid() ? bounds.min - camera : glm::dvec3(-1.0);
  const glm::dvec3 relMax = bounds.valid() ? bounds.max - camera : glm::dvec3(1.0);
  out.shadowPlan = lighting::planLightShadows(out.lights, settings.lightShadowMapSize, settings.lightShadowMaxLights, relMin, relMax);
  if (!out.shadowPlan.views.empty()) {
    const VkDeviceSize bytes = out.shadowPlan.views.size() * sizeof(shared::GpuShadowView);
    if (lightShadowViews_.size() < bytes)
      lightShadowViews_ = gpu::UploadRing(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, lighting::kLightShadowViews);
    lightShadowViews_.write(frame, out.shadowPlan.views.data(), bytes);
    graph.importBuffer(lighting::kLightShadowViews, graph::ResourceDesc::buffer(lightShadowViews_.size(), "point, spot and area light shadow views (shared/lights.h GpuShadowView[])"), lightShadowViews_.forFrame(frame));
  }
  if (!out.lights.empty()) {
    const VkDeviceSize bytes = out.lights.size() * sizeof(shared::GpuLight);
    if (lightTable_.size() < bytes)
      lightTable_ = gpu::UploadRing(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, lighting::kLightTable);
    lightTable_.write(frame, out.lights.data(), bytes);
    graph.importBuffer(lighting::kLightTable, graph::ResourceDesc::buffer(lightTable_.size(), "lights other than the sun (shared/lights.h GpuLight[])"), lightTable_.forFrame(frame));
  }
  // The environment map's table exists only in frames with a map (the reference samples it).
  if (environmentMap) {
    uploadEnvironmentTable(*environmentMap);
    graph.importBuffer(lighting::kEnvironmentTable, graph::ResourceDesc::buffer(environmentTable_.size(),
                                                      "the environment map's texels and importance table (shared/environment.h)"), environmentTable_);
  }
  return out;
}

std::string FramePipeline::addPasses(graph::RenderGraph& graph, lighting::FrameInputs& in, lighting::LightingPath& path,
                                     const FrameLights& lights, const FrameViews& views) {
  Passes& p = *passes_;
  in.accel = &accel_;
  p.gbuffer.add(graph, in);
  p.shadow.add(graph, in);
  in.lightShadowViews = uint32_t(lights.shadowPlan.views.size());
  const float nearLight = 0.05f * std::max(in.constants.sceneScale, 1e-3f);
  for (const auto& l : lights.lights) {
    const float strongest = std::max({l.intensity.x, l.intensity.y, l.intensity.z});
    in.areaLights += shared::tlIsAreaLight(l.type) ? 1u : 0u;
    in.lightTableRadiance += shared::tlIsAreaLight(l.type)           ? strongest
                             : l.type == shared::kLightDirectional ? strongest / shared::kPi
                                                                   : strongest / (shared::kPi * nearLight * nearLight);
  }
  p.lightShadow.add(graph, in, lights.shadowPlan);  // culled in paths that trace their shadows
  lighting::LightingOutputs outputs = path.addPasses(graph, in);
  // A path that computes the whole image (the reference) shades the lights itself.
  if (outputs.radiance.empty())
    outputs.lightsRadiance = p.lights.add(graph, in, outputs.shadowStructures, outputs.shadowTlasHandle);
  in.refineLights = [&p, &in, &outputs](graph::RenderGraph& g) {
    p.lights.addIbufferRefine(g, in, outputs.shadowStructures, outputs.shadowTlasHandle);
  };
  p.composite.add(graph, in, outputs);
  if (in.temporalAntialiasing) p.taa.add(graph, in);
  p.albedoView.add(graph, in);
  p.tonemap.add(graph, in);
  if (views.compare) {
    p.compareView.add(graph, in, *views.compare, views.compared, views.hasLeft, views.hasRight);
    return {};
  }
  if (!views.display) return {};
  // A resource this frame does not make (another path's, after a switch) is not an error:
  // the final image shows instead, and the caller names what was asked for.
  lighting::DisplayRequest request = *views.display;
  const auto id = request.source.empty() ? std::nullopt : graph.find(request.source);
  std::string missing;
  if (!request.source.empty() && (!id || graph.resources()[*id].desc.type != graph::ResourceType::Image)) {
    missing = request.source;
    request = lighting::DisplayRequest{.selectedInstance = request.selectedInstance};
  }
  p.display.add(graph, in, request);
  return missing;
}

}  // namespace tl::session
