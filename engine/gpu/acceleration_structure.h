// Acceleration structures for ray tracing: bottom level from a triangle mesh in GPU
// buffers, top level from instances. Builds at load time run immediately (and wait); builds
// in a frame are recorded into a render-graph pass of kind AccelerationStructureBuild, which
// places their barriers (nothing here records a barrier between passes).
#pragma once

#include "gpu/resources.h"
#include "gpu/upload_ring.h"

#include <glm/glm.hpp>

#include <vector>

namespace tl::gpu {

// What the process has built, for the tests and the benchmark that check every tracer shares
// one set of structures (lighting/common/scene_accel.h): builds made at load time (bottom
// levels, with their host wall time including the wait), builds recorded in frames (top
// levels, refits, in-place rebuilds), and the bytes of the structures alive now. Counted over
// every device; read as differences.
struct AccelerationStructureTotals {
  uint64_t bottomLevelBuilds = 0;  // buildBottomLevel, buildBottomLevelAt
  double bottomLevelBuildMs = 0.0;
  uint64_t topLevelBuilds = 0;     // buildTopLevel, TopLevelBuilder::record
  uint64_t refits = 0;             // recordRefit
  uint64_t rebuilds = 0;           // recordRebuild
  VkDeviceSize liveBytes = 0;      // every structure not yet reset (bottom and top levels)
};
AccelerationStructureTotals accelerationStructureTotals();

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  ~AccelerationStructure() { reset(); }
  AccelerationStructure(AccelerationStructure&& o) noexcept { *this = std::move(o); }
  AccelerationStructure& operator=(AccelerationStructure&& o) noexcept;
  void reset();

  VkAccelerationStructureKHR handle() const { return handle_; }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize bytes() const { return bytes_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  friend AccelerationStructure buildBottomLevel(Device&, const struct TriangleGeometry&, std::string_view, bool, bool);
  friend AccelerationStructure buildTopLevel(Device&, const std::vector<struct TlasInstance>&, std::string_view);
  friend AccelerationStructure buildBottomLevelAt(Device&, const struct TriangleGeometry&, std::string_view, const Buffer&,
                                                  VkDeviceSize, bool);
  friend class TopLevelBuilder;
  Device* device_ = nullptr;
  VkDeviceSize bytes_ = 0;
  VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
  Buffer buffer_;
  VkDeviceAddress address_ = 0;
};

struct TriangleGeometry {
  VkDeviceAddress vertices = 0;  // float3 positions at the start of each vertex
  VkDeviceSize vertexStride = 12;
  uint32_t vertexCount = 0;
  VkDeviceAddress indices = 0;   // uint32 triangle list
  uint32_t triangleCount = 0;
  bool opaque = true;
};

struct TlasInstance {
  glm::mat4 transform{1.0f};   // object -> world (camera-relative)
  uint32_t customIndex = 0;    // gl_InstanceCustomIndexEXT: index into per-instance data
  uint8_t mask = 0xFF;
  VkDeviceAddress blas = 0;
};

// Builds and waits (device.immediate). `compact`: build, query the compacted size and copy
// into a structure of exactly that size (the driver's worst-case estimate is often 2x).
// `allowUpdate`: the structure can be refitted in place when its vertices move (its
// triangles stay); such a structure is not compacted (compaction would drop that ability on
// some drivers, and the refit needs the build's size anyway).
AccelerationStructure buildBottomLevel(Device& device, const TriangleGeometry& geometry, std::string_view name,
                                       bool compact = false, bool allowUpdate = false);
// Bottom levels side by side in one buffer the caller owns (so a frame graph can name them
// as one resource): bottomLevelBytes() sizes each (rounded to the 256-byte placement
// alignment), buildBottomLevelAt() builds one at an offset of `storage` (created with
// VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR) and waits.
VkDeviceSize bottomLevelBytes(Device& device, const TriangleGeometry& geometry, bool allowUpdate);
AccelerationStructure buildBottomLevelAt(Device& device, const TriangleGeometry& geometry, std::string_view name,
                                         const Buffer& storage, VkDeviceSize offset, bool allowUpdate);
// Scratch bytes a refit (or an in-place rebuild) of `geometry` needs, alignment included: the
// caller's scratch buffer holds one such range per build recorded together.
VkDeviceSize refitScratchBytes(Device& device, const TriangleGeometry& geometry);
VkDeviceSize rebuildScratchBytes(Device& device, const TriangleGeometry& geometry);
// Records an in-place refit of a bottom level built with allowUpdate from the same geometry,
// reading its vertices as they are now, with scratch at `scratchOffset` of `scratch`.
// Recorded inside a render-graph pass of kind AccelerationStructureBuild, which places every
// barrier around it (vertex writes before, acceleration-structure reads after).
void recordRefit(VkCommandBuffer cmd, Device& device, const AccelerationStructure& blas, const TriangleGeometry& geometry,
                 const Buffer& scratch, VkDeviceSize scratchOffset);
// Records a full build of `geometry` into an existing bottom level made for the same geometry
// without allowUpdate (buildBottomLevelAt); the same contract as recordRefit.
void recordRebuild(VkCommandBuffer cmd, Device& device, const AccelerationStructure& blas, const TriangleGeometry& geometry,
                   const Buffer& scratch, VkDeviceSize scratchOffset);
AccelerationStructure buildTopLevel(Device& device, const std::vector<TlasInstance>& instances, std::string_view name);

// A top level rebuilt from scratch inside a command buffer (Metro: "TLAS = rebuild only from
// scratch"): storage and the instance upload buffer grow to the largest instance count seen
// and are reused; each frame in flight has its own instance upload (prepare() takes the
// executor's frame). The caller records the build inside a render-graph pass of kind
// AccelerationStructureBuild, which derives its barriers: the pass reads instances() as
// BuildInput (and any bottom levels it writes in the frame), writes storage() and a transient
// scratch buffer of scratchBytes().
class TopLevelBuilder {
 public:
  TopLevelBuilder() = default;
  TopLevelBuilder(Device& device, std::string name) : device_(&device), name_(std::move(name)) {}
  // Sizes everything for `instances.size()` and uploads the instances (host side) into
  // frame `frame`'s copy, which instances() and record() then use.
  void prepare(const std::vector<TlasInstance>& instances, uint64_t frame);
  // Records the build, with `scratch` (at least scratchBytes()); no barriers.
  void record(VkCommandBuffer cmd, const Buffer& scratch);
  const AccelerationStructure& structure() const { return structure_; }
  Buffer& storage() { return structure_.buffer_; }
  Buffer& instances() { return instances_.forFrame(frame_); }
  VkDeviceSize scratchBytes() const { return scratchBytes_; }
  uint32_t instanceCount() const { return count_; }
  explicit operator bool() const { return bool(structure_); }

 private:
  Device* device_ = nullptr;
  std::string name_;
  AccelerationStructure structure_;
  UploadRing instances_;
  uint64_t frame_ = 0;
  VkDeviceSize scratchBytes_ = 0;
  uint32_t capacity_ = 0, count_ = 0;
};

}  // namespace tl::gpu
