#include "lighting/rt/rt_scene.h"

#include "lighting/common/emitter_table.h"

#include "scene/material_average.h"

#include <algorithm>

namespace tl::lighting {

RtScene::RtScene(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene,
                 const std::vector<VkDeviceAddress>& meshIndices) {
  const auto& ranges = gpuScene.meshRanges();
  const VkDeviceAddress vertices = gpuScene.vertexBuffer().address();
  // Once per material (texture averages touch every texel), then per instance. The albedo
  // is the texture-average fallback until setInstanceAlbedo() gives the resolved one.
  std::vector<glm::vec4> albedo, emission;
  std::vector<glm::vec3> modeAlbedo[3];
  for (const auto& m : scene.materials) {
    albedo.push_back(glm::vec4(scene::materialAverageAlbedo(scene, m), 0.0f));
    emission.push_back(glm::vec4(scene::materialAverageEmission(scene, m), 0.0f));
    for (uint32_t mode = 0; mode < 3; ++mode) modeAlbedo[mode].push_back(scene::materialAverageAlbedo(scene, m, mode));
  }
  std::vector<shared::RtInstance>& data = instances_;
  data.assign(std::max<size_t>(1, scene.instances.size()), shared::RtInstance{});
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const uint32_t mesh = scene.instances[i].mesh;
    data[i].albedo = albedo[scene.meshes[mesh].material];
    data[i].albedoScale = glm::vec4(1.0f);
    data[i].emission = emission[scene.meshes[mesh].material];
    data[i].material = scene.meshes[mesh].material;
    const VkDeviceAddress ia = meshIndices[mesh];
    const VkDeviceAddress va = vertices + VkDeviceAddress(ranges[mesh].vertexOffset) * sizeof(scene::Vertex);
    data[i].indexAddress = glm::uvec2(uint32_t(ia), uint32_t(ia >> 32));
    data[i].vertexAddress = glm::uvec2(uint32_t(va), uint32_t(va >> 32));
  }
  for (uint32_t mode = 0; mode < 3; ++mode)
    for (size_t i = 0; i < scene.instances.size(); ++i)
      fallbackAlbedo_[mode].push_back(modeAlbedo[mode][scene.meshes[scene.instances[i].mesh].material]);
  instanceData_ = gpu::UploadRing(device, data.size() * sizeof(data[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "rt.instanceData");
  instanceData_.write(0, data.data(), data.size() * sizeof(data[0]));  // new copies: no frame uses them yet

  std::vector<glm::vec3> instanceEmission;
  for (size_t i = 0; i < scene.instances.size(); ++i) instanceEmission.push_back(glm::vec3(data[i].emission));
  std::vector<shared::Emitter> emitters = buildEmitterTable(scene, instanceEmission).entries;
  emitterCount_ = uint32_t(emitters.size());
  for (const shared::Emitter& e : emitters)
    maxEmitterRadiance_ = std::max({maxEmitterRadiance_, e.radiance.x, e.radiance.y, e.radiance.z});
  if (emitters.empty()) emitters.push_back(shared::Emitter{});  // a binding needs a buffer
  emitterData_ = gpu::Buffer(device, emitters.size() * sizeof(emitters[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             gpu::MemoryUsage::Upload, "rt.emitters");
  emitterData_.write(emitters.data(), emitters.size() * sizeof(emitters[0]));
}

void RtScene::setInstanceAlbedo(const std::vector<glm::vec4>* resolved, uint32_t materials, uint64_t frame) {
  const std::vector<glm::vec3>& fallback = fallbackAlbedo_[std::min(materials, 2u)];
  for (size_t i = 0; i < fallback.size(); ++i) {
    const bool authored = materials == shared::kMaterialsAuthored && resolved && i < resolved->size();
    const glm::vec3 albedo = authored ? glm::vec3((*resolved)[i]) : fallback[i];
    instances_[i].albedo = glm::vec4(albedo, 0.0f);
    // Pre-traced hits read the G-buffer, which already shows the mode: only an override or a
    // database entry re-colours them.
    instances_[i].albedoScale = glm::vec4(albedo / glm::max(fallback[i], glm::vec3(1e-4f)), 0.0f);
  }
  instanceData_.write(frame, instances_.data(), instances_.size() * sizeof(instances_[0]));
}

}  // namespace tl::lighting
