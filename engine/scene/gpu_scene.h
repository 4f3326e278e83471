// The scene on the GPU: one vertex and one index buffer for all meshes, the material
// table, the per-frame camera-relative instance table, and the texture table, bound
// together as descriptor set kSceneSet. Passes draw it with drawAll(), one multi-draw call
// for all its instances.
#pragma once

#include "gpu/descriptor_table.h"
#include "gpu/draw_arena.h"
#include "gpu/resources.h"
#include "gpu/upload_ring.h"
#include "graph/executor.h"
#include "graph/graph.h"
#include "scene/scene.h"

#include <optional>
#include <vector>

namespace tl::scene {

// The scene's buffers as a frame graph sees them (imported: owned by GpuScene).
inline constexpr graph::BufferName kSceneVertices{"scene.vertices"};
inline constexpr graph::BufferName kSceneIndices{"scene.indices"};
inline constexpr graph::BufferName kSceneInstances{"scene.instances"};
inline constexpr graph::BufferName kSceneMaterials{"scene.materials"};
// Deforming meshes' positions of the last frame (vec4 each), for the motion vectors; only in
// scenes that deform.
inline constexpr graph::BufferName kScenePreviousPositions{"scene.vertices.previous"};
// This frame's instance table as the host wrote it; a transfer pass copies it into kSceneInstances.
inline constexpr graph::BufferName kSceneInstanceUpload{"scene.instances.upload"};

// The Vulkan format a texture is uploaded in: its TexelFormat, sRGB-decoded by the sampler
// where an 8-bit texture holds colour.
VkFormat textureFormat(const Texture& texture);

class GpuScene {
 public:
  GpuScene(gpu::Device& device, const Scene& scene);

  // Vertex input of tl::scene::Vertex for raster pipelines.
  static std::vector<VkVertexInputBindingDescription> vertexBindings();
  static std::vector<VkVertexInputAttributeDescription> vertexAttributes();

  // Rewrites the instance table relative to `camera` (double precision on the CPU) for the
  // executor's frame `frame`: into an upload copy of that frame, which importBuffers() has
  // the frame copy into the table the passes read (frames in flight read their own copies,
  // and the table's descriptor never changes). `previousCamera` and the previous transforms
  // make the motion vectors.
  void updateInstances(const Scene& scene, const glm::dvec3& camera, const glm::dvec3& previousCamera, uint64_t frame);

  // Replaces the vertices of deforming meshes (morph targets, skins) in one upload, between
  // frames, keeping the positions they replace as kScenePreviousPositions (the motion vectors'
  // last frame). Call it every frame of a deforming scene, with no meshes when none changed: a
  // mesh that stops moving then gets previous = present. `vertices[i]` must have mesh
  // `meshes[i]`'s vertex count. No frame may be in flight when it writes (writesPending()).
  void updateMeshVertices(const std::vector<uint32_t>& meshes, const std::vector<std::vector<Vertex>>& vertices);
  // Whether updateMeshVertices() with no meshes would still write (meshes stop moving).
  bool writesPending() const { return !movedLastUpdate_.empty(); }
  // The scene has deforming meshes (and the buffer kScenePreviousPositions).
  bool deforms() const { return previousPositions_.handle() != VK_NULL_HANDLE; }
  // Counts vertex updates: per mesh, and of the whole scene (0 until something deforms).
  uint64_t meshVersion(uint32_t mesh) const { return meshVersions_[mesh]; }
  uint64_t geometryVersion() const { return geometryVersion_; }

  // Imports the four buffers above into `graph`; when updateInstances() wrote for `frame`,
  // also the pass that uploads the instances.
  void importBuffers(graph::RenderGraph& graph, uint64_t frame);

  // Binds the geometry and draws every instance (instance index via firstInstance), in the
  // pass `ctx` records: one multi-draw call for all of them (gpu/draw_arena.h).
  void drawAll(graph::PassContext& ctx) const;
  // Binds the geometry and draws the listed instances only, in one call.
  void drawInstances(graph::PassContext& ctx, const std::vector<uint32_t>& instances) const;
  // Draws the listed instances without vertex or index buffers, in one call: vertex k of
  // instance i is gl_VertexIndex = its mesh's firstIndex + k (a multiple of 3 starts each
  // mesh's triangles), for shaders that fetch whole triangles from the buffers themselves
  // (GpuInstance::vertexOffset).
  void drawInstancesUnindexed(graph::PassContext& ctx, const std::vector<uint32_t>& instances) const;
  // Draw calls recorded since the scene was made and the instance draws they held.
  uint64_t drawCalls() const { return drawArena_.calls(); }
  uint64_t instanceDraws() const { return drawArena_.draws(); }
  // Binds the vertex and index buffers; then drawMesh() draws one mesh once (instance 0),
  // for passes that place meshes themselves (the albedo baker).
  void bindGeometry(VkCommandBuffer cmd) const;
  void drawMesh(VkCommandBuffer cmd, uint32_t mesh) const;

  // Instances whose material is alpha-tested (MASK cut-outs, BLEND's stochastic transparency,
  // and transmission, which the G-buffer paths draw as stochastic coverage: shared/scene.h
  // tlTransmissionCutout) and all the others: passes that only need depth (the shadow maps) draw the opaque ones
  // without a fragment stage.
  const std::vector<uint32_t>& alphaTestedInstances() const { return alphaTested_; }
  const std::vector<uint32_t>& opaqueInstances() const { return opaque_; }
  // Per mesh: its material is alpha-tested or transmits (ray tracing keeps such meshes
  // non-opaque: any-hit shaders cut them out or pass their transmittance on).
  bool meshAlphaTested(uint32_t mesh) const { return meshAlphaTested_.at(mesh) != 0; }

  const gpu::DescriptorTable& table() const { return table_; }
  gpu::Buffer& vertexBuffer() { return vertices_; }
  gpu::Buffer& indexBuffer() { return indices_; }
  gpu::Buffer& instanceBuffer() { return instances_; }
  gpu::Buffer& materialBuffer() { return materials_; }
  size_t instanceCount() const { return drawMesh_.size(); }
  // Distinct for every GpuScene made in this process (an address could be reused).
  uint64_t id() const { return id_; }
  struct MeshRange {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t vertexCount = 0;
    uint32_t material = 0;
  };
  // Where each mesh lives in the shared buffers, and which mesh each instance draws: what
  // acceleration structures and hit shaders need.
  const std::vector<MeshRange>& meshRanges() const { return meshes_; }
  uint32_t instanceMesh(size_t instance) const { return drawMesh_[instance]; }
  // This frame's camera-relative object -> world transforms, one per instance.
  const std::vector<glm::mat4>& relativeTransforms() const { return relative_; }
  VkDeviceSize bytes() const;

 private:
  VkDrawIndexedIndirectCommand indexedDrawOf(uint32_t instance) const;

  gpu::Device& device_;
  uint64_t id_ = 0;
  gpu::Buffer vertices_, indices_, materials_, instances_;
  gpu::UploadRing instanceUploads_;
  std::optional<uint64_t> uploadFrame_;  // the frame the last updateInstances() wrote for
  std::vector<gpu::Image> textures_;
  std::vector<SamplerMode> samplerModes_;  // distinct modes, one Vulkan sampler each
  std::vector<gpu::Sampler> samplers_;
  gpu::DescriptorTable table_;
  // The draw calls' arguments: memory for recording, not the scene's state (hence mutable).
  mutable gpu::DrawArena drawArena_;
  std::vector<MeshRange> meshes_;
  std::vector<uint32_t> drawMesh_;             // per instance: its mesh
  std::vector<uint32_t> alphaTested_, opaque_;  // instance lists
  std::vector<uint8_t> meshAlphaTested_;
  std::vector<glm::dmat4> previousTransforms_;  // per instance, world
  std::vector<glm::mat4> relative_;             // per instance, camera-relative
  bool havePrevious_ = false;
  std::vector<uint64_t> meshVersions_;
  gpu::Buffer previousPositions_;                       // only in scenes that deform
  std::vector<uint32_t> previousOffset_;                // per mesh, or shared::kNoPreviousPositions
  std::vector<std::vector<glm::vec4>> uploadedPositions_;  // per deforming mesh: what the vertex buffer holds
  std::vector<uint32_t> movedLastUpdate_;               // meshes the last update moved
  uint64_t geometryVersion_ = 0;
};

}  // namespace tl::scene
