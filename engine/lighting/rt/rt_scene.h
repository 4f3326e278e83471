// The RT module's geometry (Metro: "a separate mini-engine"): one bottom-level structure
// per mesh built from a simplified RT mesh, compacted; the per-instance hit data; and the
// top level rebuilt every frame from the instances that survive culling.
#pragma once

#include "gpu/acceleration_structure.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/rt/blas_refit.h"
#include "shared/rt.h"

#include <limits>
#include <vector>

namespace tl::lighting {

struct RtSceneStats {
  uint64_t sourceTriangles = 0;
  uint64_t rtTriangles = 0;       // after simplification
  VkDeviceSize blasBytes = 0;     // compacted
  double blasBuildMs = 0.0;       // CPU wall time of simplify + build + compact, all meshes
  float maxDeviation = 0.0f;      // largest simplification error in world metres
  // Deforming meshes (morph targets): their bottom levels, refitted under the throttle.
  uint32_t deformingMeshes = 0;
  VkDeviceSize deformingBytes = 0;
  uint32_t staleLastFrame = 0;    // deforming meshes whose vertices moved since their last refit
  uint32_t refitsLastFrame = 0;   // of those, refitted this frame
  uint64_t refitVerticesLastFrame = 0;
};

// Which instances go into this frame's top level.
struct RtCulling {
  glm::mat4 viewProj{1.0f};  // camera-relative
  float margin = 0.0f;       // expanded frustum, metres added to every plane
  float minAngle = 0.0f;     // contribution culling: bounding-sphere radius / distance below this is dropped
  // Distance culling: farther than this (nearest point from the camera) is dropped. Beyond
  // the GI blend distance the path's GI is not used (the far field's or the sky's is), so the
  // rays that matter start nearer than it and reach at most the margin beyond.
  float maxDistance = std::numeric_limits<float>::infinity();
};

// Pure: the culled, spatially ordered instance list (indices into the scene's instances).
// `centres`/`radii` are camera-relative bounding spheres. Tested without a GPU.
std::vector<uint32_t> cullInstances(const std::vector<glm::vec3>& centres, const std::vector<float>& radii,
                                    const RtCulling& culling);

// A triangle list reduced to about `ratio` of its triangles within `maxError` (relative to
// the mesh size), then spatially sorted (lavapipe's BVH builder splits in input order).
// `deviation` receives the error in the mesh's units. ratio >= 1 keeps every triangle.
std::vector<uint32_t> simplifyForRayTracing(const std::vector<scene::Vertex>& vertices,
                                            const std::vector<uint32_t>& indices, float ratio, float maxError,
                                            float* deviation);

class RtScene {
 public:
  RtScene(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene, float simplifyRatio,
          float simplifyError);

  // Chooses this frame's instances and uploads them, and which deforming meshes to refit;
  // recordRefits() then topLevel().record() build them, each in a graph pass of kind
  // AccelerationStructureBuild (the graph places the barriers).
  void prepareTopLevel(const scene::GpuScene& gpuScene, const RtCulling& culling, uint64_t frame, const RefitPolicy& refits = {});
  bool refitsPending() const { return !pendingRefits_.empty(); }
  // Scratch for every deforming mesh refitted at once: what the refit pass creates.
  VkDeviceSize refitScratchBytes() const { return refitScratchBytes_; }
  // Refits the bottom levels chosen by prepareTopLevel from the scene's current vertices,
  // into deformingStorage(), with `scratch` of refitScratchBytes().
  void recordRefits(VkCommandBuffer cmd, const gpu::Buffer& scratch);
  bool hasDeforming() const { return stats_.deformingMeshes > 0; }
  // All deforming meshes' bottom levels, side by side: the graph's rt.blas.deforming.
  gpu::Buffer& deformingStorage() { return deformingStorage_; }
  gpu::TopLevelBuilder& topLevel() { return topLevel_; }
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
  const RtSceneStats& stats() const { return stats_; }
  uint32_t instancesInTopLevel() const { return topLevel_.instanceCount(); }
  float simplifyRatio() const { return ratio_; }

 private:
  std::vector<gpu::AccelerationStructure> blas_;  // per mesh
  std::vector<gpu::Buffer> rtIndices_;            // per mesh: the simplified triangle list
  std::vector<glm::vec3> meshCentre_;             // object space bounding sphere per mesh
  std::vector<float> meshRadius_;
  std::vector<shared::RtInstance> instances_;     // CPU copy of instanceData_
  // Per material override mode, per instance: its material's texture-average albedo.
  std::vector<glm::vec3> fallbackAlbedo_[3];
  gpu::UploadRing instanceData_;                  // RtInstance per scene instance
  gpu::Buffer emitterData_;                       // shared::Emitter per emissive triangle
  uint32_t emitterCount_ = 0;
  float maxEmitterRadiance_ = 0.0f;
  gpu::TopLevelBuilder topLevel_;
  RtSceneStats stats_;
  float ratio_ = 1.0f;
  // Deforming meshes: geometry as built, the mesh version each bottom level holds, each one's
  // range of the refit scratch (refits of one frame run together), the throttle and this
  // frame's choice.
  std::vector<gpu::TriangleGeometry> geometry_;  // per mesh
  std::vector<int64_t> meshInstance_;             // per mesh: its one instance (deforming meshes), else -1
  std::vector<uint64_t> refitVersion_;            // per mesh
  std::vector<VkDeviceSize> refitScratchOffset_;  // per mesh (0 for still ones)
  VkDeviceSize refitScratchBytes_ = 0;
  gpu::Buffer deformingStorage_;
  RefitScheduler scheduler_;
  std::vector<std::pair<uint32_t, uint64_t>> pendingRefits_;  // mesh, the version it will hold
  uint64_t frame_ = 0;
  gpu::Device* device_ = nullptr;
};

}  // namespace tl::lighting
