// What the RT path's hits read about the scene, beside the acceleration structures it borrows
// (lighting/common/scene_accel.h, the simplified level): per instance its hit albedo, emission,
// material and the addresses of its triangles as the bottom level holds them; the emissive
// triangles for next-event estimation.
#pragma once

#include "gpu/upload_ring.h"
#include "lighting/common/frame_inputs.h"
#include "shared/rt.h"

#include <vector>

namespace tl::lighting {

class RtScene {
 public:
  // `meshIndices`: per mesh, the triangle list the simplified bottom level was built from
  // (SceneAccel::meshIndices).
  RtScene(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene,
          const std::vector<VkDeviceAddress>& meshIndices);

  // Frame `frame`'s copy of the instance table (gpu::UploadRing: albedo edits while frames are in flight).
  gpu::Buffer& instanceData(uint64_t frame) { return instanceData_.forFrame(frame); }
  // The emissive triangles (lighting/common/emitter_table.h): at least one entry, emitterCount() valid.
  gpu::Buffer& emitterData() { return emitterData_; }
  uint32_t emitterCount() const { return emitterCount_; }
  float maxEmitterRadiance() const { return maxEmitterRadiance_; }  // the brightest channel of any emitter
  // Per-instance hit albedo under a material override mode (shared/material_mode.h): as
  // authored, the one resolved outside (engine/albedo/: override > baked > texture average; null: texture
  // averages); in the Lambertian modes what the mode reflects (the base colour's texture
  // average, or the clay albedo), which no override or database entry changes. Until called,
  // each instance has its material's authored texture average.
  void setInstanceAlbedo(const std::vector<glm::vec4>* resolved, uint32_t materials, uint64_t frame);

 private:
  std::vector<shared::RtInstance> instances_;     // CPU copy of instanceData_
  // Per material override mode, per instance: its material's texture-average albedo.
  std::vector<glm::vec3> fallbackAlbedo_[3];
  gpu::UploadRing instanceData_;                  // RtInstance per scene instance
  gpu::Buffer emitterData_;                       // shared::Emitter per emissive triangle
  uint32_t emitterCount_ = 0;
  float maxEmitterRadiance_ = 0.0f;
};

}  // namespace tl::lighting
