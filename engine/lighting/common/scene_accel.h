// The scene's acceleration structures, built once and borrowed by every tracer (the rt path,
// the reference, the plugins, and through a path's outputs the light table's shadow rays and
// the hybrid sun shadow). The session's FramePipeline owns the one SceneAccel and hands it to
// the paths in FrameInputs::accel; no path builds a structure of its own. Two levels of
// detail, each built the first time a frame asks for it:
//
//   Simplified: each mesh reduced to about rtSimplifyRatio of its triangles (cut-outs and
//     deforming meshes keep all of theirs), compacted; deforming meshes refitted in place under
//     a throttle (RefitScheduler); the top level rebuilt every frame from the instances that
//     survive culling (Metro: "TLAS = rebuild only from scratch"). What real-time tracers trace.
//   Full: every triangle, read from the scene's own index buffer; deforming meshes rebuilt
//     exactly when their vertices move; the top level holds every instance and is rebuilt only
//     when a transform or a bottom level changed. What the ground truth traces.
//
// A level's bottom levels are built again only for a new scene (GpuScene::id) or, for the
// simplified level, new simplification settings; its passes (refit or rebuild, top level) join
// a frame's graph once, however many tracers ask in that frame.
#pragma once

#include "gpu/acceleration_structure.h"
#include "lighting/common/blas_refit.h"
#include "lighting/common/frame_inputs.h"

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace tl::lighting {

enum class AccelDetail : uint8_t { Simplified, Full };

// The graph's names of a level's structures and of its passes' scratch.
struct AccelNames {
  const char* tlas;           // imported: the top level
  graph::BufferName tlasInstances;  // imported: its instance list (host-written)
  const char* tlasScratch;
  const char* blasDeforming;  // imported: the deforming meshes' bottom levels, side by side
  const char* blasScratch;    // scratch of their refits (simplified) or rebuilds (full)
  const char* updatePass;     // the pass that refits or rebuilds them
  const char* tlasPass;       // the pass that builds the top level
};
inline constexpr AccelNames kAccelSimplified{"accel.simplified.tlas",
                                             graph::BufferName{"accel.simplified.tlas.instances"},
                                             "accel.simplified.tlas.scratch", "accel.simplified.blas.deforming",
                                             "accel.simplified.blas.refitScratch", "accel.simplified.blas.refit",
                                             "accel.simplified.tlas"};
inline constexpr AccelNames kAccelFull{"accel.full.tlas", graph::BufferName{"accel.full.tlas.instances"}, "accel.full.tlas.scratch",
                                       "accel.full.blas.deforming", "accel.full.blas.rebuildScratch",
                                       "accel.full.blas.rebuild", "accel.full.tlas"};

// What a trace binds: the top level, and the graph names of what it reads through it (the top
// level, then the bottom levels a frame may rewrite), for the pass builders'
// accelerationStructure(binding, tlas, names).
struct TraceStructures {
  VkAccelerationStructureKHR tlas = VK_NULL_HANDLE;
  std::vector<std::string> names;
};

struct AccelStats {
  uint64_t sourceTriangles = 0;
  uint64_t triangles = 0;         // in the bottom levels (after simplification)
  VkDeviceSize blasBytes = 0;     // compacted where the level compacts
  double blasBuildMs = 0.0;       // CPU wall time of simplify + build + compact, all meshes
  float maxDeviation = 0.0f;      // largest simplification error in world units
  uint32_t meshes = 0;
  // Deforming meshes (morph targets, skins): their bottom levels, refitted or rebuilt.
  uint32_t deformingMeshes = 0;
  VkDeviceSize deformingBytes = 0;
  uint32_t staleLastFrame = 0;    // deforming meshes whose vertices moved since their last refit
  uint32_t refitsLastFrame = 0;   // of those, refitted (or rebuilt) this frame
  uint64_t refitVerticesLastFrame = 0;
  uint32_t instancesInTopLevel = 0;
  uint32_t sceneInstances = 0;
};

// Which instances go into a culled top level.
struct RtCulling {
  glm::mat4 viewProj{1.0f};  // camera-relative
  float margin = 0.0f;       // expanded frustum, units added to every plane
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

// The culling the simplified top level applies this frame, from the settings (resolved) and
// the camera: the rt path's ray reach around the view frustum, to its GI blend distance.
RtCulling simplifiedCulling(const FrameInputs& in);

class SceneAccel {
 public:
  SceneAccel();
  ~SceneAccel();
  SceneAccel(const SceneAccel&) = delete;
  SceneAccel& operator=(const SceneAccel&) = delete;

  // This frame's structures at `detail`: the level is built for the frame's scene if it is not
  // (waiting for the device), and its passes join `graph` unless an earlier call added them to it.
  const TraceStructures& addPasses(graph::RenderGraph& graph, FrameInputs& in, AccelDetail detail);

  // What the level holds now (zeros before it is built).
  const AccelStats& stats(AccelDetail detail) const;
  // Per mesh: the device address of the uint32 triangle list its bottom level was built from
  // (the hit shaders read a hit's triangle there). Empty before the level is built.
  const std::vector<VkDeviceAddress>& meshIndices(AccelDetail detail) const;
  // Changes whenever the level is built anew (a new scene, new simplification settings): what
  // a tracer derived from it (per-instance hit data) is to be made again.
  uint64_t generation(AccelDetail detail) const;

 private:
  struct Level;
  std::array<std::unique_ptr<Level>, 2> levels_;
  uint64_t generations_ = 0;
};

// The frame's structures at `detail` from the frame's SceneAccel (FrameInputs::accel, which the
// session sets; a frame without one is a programming error, reported as such).
const TraceStructures& traceStructures(graph::RenderGraph& graph, FrameInputs& in, AccelDetail detail);

}  // namespace tl::lighting
