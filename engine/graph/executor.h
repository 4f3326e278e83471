// Runs a compiled render graph on the device. The executor owns the cross-cutting work so
// pass code never does it: physical images (transients placed in one aliased block,
// persistent history kept across frames), barriers, debug labels and GPU timestamps named
// after the pass, and read-back of any resource by name after the frame.
#pragma once

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/timestamps.h"
#include "graph/graph.h"

#include <glm/glm.hpp>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace tl::graph {

struct Attachment {
  std::string name;
  std::optional<glm::vec4> clearColor;  // colour: clear to this, else load
  std::optional<float> clearDepth;      // depth: clear to this, else load
};

// What a pass's execute function gets. Resource access is checked against what the pass
// declared in setup: touching an undeclared resource throws with both names.
class PassContext {
 public:
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  gpu::Device& device;
  uint64_t frameIndex = 0;

  const gpu::Image& image(std::string_view name) const;
  const gpu::Buffer& buffer(std::string_view name) const;
  VkExtent3D extent(std::string_view name) const { return image(name).extent(); }
  // True when a persistent resource holds last frame's contents (false after creation or resize).
  bool historyValid(std::string_view name) const;
  // The layout the graph put an image in for this pass (what its descriptors must say): the
  // usage's layout, or the merged one when the pass uses the image two ways (graph.h).
  VkImageLayout layout(std::string_view name) const;

  // `area`: the render area when there are no attachments (e.g. voxelization into storage images).
  void beginRendering(const std::vector<Attachment>& colors, const std::optional<Attachment>& depth,
                      std::optional<VkExtent2D> area = std::nullopt);
  void endRendering();
  // Draws into a sub-rectangle of the attachments (viewport and scissor); beginRendering()
  // resets it to the whole area.
  void setViewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height);
  // Draws only into a sub-rectangle, keeping the viewport (a region of a voxelizing raster).
  void setScissor(uint32_t x, uint32_t y, uint32_t width, uint32_t height);

  void bind(const gpu::Pipeline& pipeline);
  gpu::DescriptorWriter& descriptors() { return writer_; }
  template <class T>
  void pushConstants(const T& data) { pushConstantBytes(&data, sizeof(T)); }
  void pushConstantBytes(const void* data, uint32_t bytes);
  // Pushes the pending descriptors, then dispatches ceil(size / local) groups.
  void dispatch(uint32_t width, uint32_t height, uint32_t depth = 1, uint32_t localX = 8, uint32_t localY = 8,
                uint32_t localZ = 1);
  void flushDescriptors();

 private:
  friend class Executor;
  PassContext(gpu::Device& d, class Executor& e, const RenderGraph& g, const PassDecl& p, const CompiledPass& c)
      : device(d), executor_(e), graph_(g), pass_(p), compiled_(c) {}
  bool declares(std::string_view name) const;
  Executor& executor_;
  const RenderGraph& graph_;
  const PassDecl& pass_;
  const CompiledPass& compiled_;
  const gpu::Pipeline* bound_ = nullptr;
  gpu::DescriptorWriter writer_;
};

struct PassTiming {
  std::string pass;
  double gpuMs = 0.0;
};

// One resource as the executor realised it, for the dump, the inspector and captures.
struct PhysicalInfo {
  std::string name;
  ResourceDesc desc;
  std::string writer;           // pass name, or "(imported)" / "(previous frame)"
  uint32_t firstUse = kNone, lastUse = kNone;
  bool persistent = false, imported = false, aliased = false;
  VkDeviceSize offset = 0;      // in the transient block when aliased
  VkDeviceSize bytes = 0;
};

struct Readback {
  std::string name;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{};
  std::vector<uint8_t> bytes;   // tightly packed texels or buffer bytes
  uint64_t frame = 0;           // the executor's number of the frame it was read from
  std::vector<float> texels() const;  // decoded, channels per texel from the format
  uint32_t channels() const;
};

class Executor {
 public:
  explicit Executor(gpu::Device& device);
  ~Executor();

  // Resources owned outside the graph; bind before every compile and execute that imports
  // them. An image is handed back in `currentLayout` at the end of the frame, and the executor
  // then forgets the binding (its owner may free what it bound), remembering each import's
  // last accesses by name and handle so the next frame that binds the same object waits for
  // them. unbindImported() drops bindings made for a frame that was not executed.
  void bindImportedImage(std::string_view name, gpu::Image& image, VkImageLayout currentLayout);
  void bindImportedBuffer(std::string_view name, gpu::Buffer& buffer);
  void unbindImported();

  // The states the persistent and imported resources of `graph` enter the next frame in:
  // what the previous frames left (layout, last write, reads since). Compile with them:
  // graph.compile(executor.entryStates(graph)). A persistent resource the graph declares with
  // another description is recreated, so it enters fresh.
  EntryStates entryStates(const RenderGraph& graph) const;
  // Binds the buffers `graph` imports with importBuffer() and compiles it from the states
  // they and the persistent resources enter the frame in.
  CompiledGraph compile(const RenderGraph& graph);

  // Read-back requests for the next execute: names, or every resource of the frame (with
  // those the graph carries, RenderGraph::requestReadback).
  void requestReadback(std::string_view name) { readbackNames_.insert(std::string(name)); }
  void requestReadbackAll() { readbackAll_ = true; }

  // Records and submits the frame, waits for it, then collects timings and read-backs.
  // `compiled` must come from entryStates() of this executor (checked).
  void execute(const RenderGraph& graph, const CompiledGraph& compiled);
  // The same in two halves, so a caller can record the next frame while the GPU works:
  // submit() records and submits without waiting; finish() waits for the oldest frame in
  // flight (if the GPU is not done yet) and collects its timings and read-backs. Up to
  // gpu::kMaxFramesInFlight frames may be in flight: submit() refuses one more. Until a
  // frame is finished, timings(), readbacks() and resources() describe the last finished one
  // (what an interface shows stays with the frame on screen). Frames run on the GPU in submission order: the next frame
  // waits for the one before at its start (the transients share memory) and persistent and
  // imported resources carry their accesses across, so what a frame writes is history for
  // the next frame as soon as it is submitted.
  void submit(const RenderGraph& graph, const CompiledGraph& compiled);
  bool inFlight() const { return submitted_ > finished_; }
  uint32_t framesInFlight() const { return uint32_t(submitted_ - finished_); }
  bool frameDone() const;  // true when finish() would not wait
  void finish();
  void finishAll() {
    while (inFlight()) finish();
  }
  // Frames submitted so far: the index of the frame recorded next. Host-written buffers
  // that frames in flight share take their copy by it (gpu::UploadRing::forFrame).
  uint64_t nextFrame() const { return submitted_; }

  const std::vector<PassTiming>& timings() const { return timings_; }
  const std::vector<PhysicalInfo>& resources() const { return physicalInfo_; }
  const std::map<std::string, Readback>& readbacks() const { return readbacks_; }
  const Readback& readback(std::string_view name) const;
  VkDeviceSize transientBytes() const { return transientBlock_.size(); }
  // The physical image of a resource after the frame, and the layout it was left in
  // (the editor blits the display image from it); nullptr when there is none.
  const gpu::Image* image(std::string_view name) const;
  VkImageLayout layout(std::string_view name) const;
  // Whether a persistent resource holds a previous frame's contents (false when unknown).
  bool historyValid(std::string_view name) const;
  // The same, asked while building a graph: also false when this frame declares it with
  // another description (a resize), which recreates it with undefined contents.
  bool historyValid(std::string_view name, const ResourceDesc& declared) const;
  // Layout an imported image was left in by the frame: the one it was bound with.
  VkImageLayout importedLayout(std::string_view name) const;
  // Drops persistent history (e.g. a camera cut or a scene change).
  void resetHistory();
  // How many times the history was dropped: state a pass keeps outside the graph's resources
  // (a decision measured over frames) starts over when it changes.
  uint64_t historyResets() const { return historyResets_; }

 private:
  friend class PassContext;
  struct FrameSlot;
  void bindGraphImports(const RenderGraph& graph);
  struct Physical {
    ResourceDesc desc;
    gpu::Image ownedImage;
    gpu::Buffer ownedBuffer;
    gpu::Image* image = nullptr;
    gpu::Buffer* buffer = nullptr;
    ResourceState state;                // what the barrier model knows, carried across frames
    VkImageLayout boundLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // imported images: the owner's layout
    StageAccess aliasWait;              // transients: the earlier users of its aliased bytes
    bool historyValid = false;
    enum class Kind : uint8_t { Transient, Persistent, Imported } kind = Kind::Transient;
  };
  Physical& find(std::string_view name);
  Physical& importSlot(std::string_view name);
  uint64_t historyResets_ = 0;

  void realise(const RenderGraph& graph, const CompiledGraph& compiled);
  void checkEntry(const RenderGraph& graph, const CompiledGraph& compiled);
  void placeBarriers(VkCommandBuffer cmd, const RenderGraph& graph, const CompiledPass& pass);
  // Copies a resource into a read-back buffer. Mid-frame, right after its writer (`writer`
  // set): the resource is returned to the state the compiled barriers expect. Otherwise the
  // copy is one more access in its carried state.
  void copyForReadback(VkCommandBuffer cmd, FrameSlot& slot, const std::string& name, Physical& p, const PassAccess* writer);
  void handBackImports(VkCommandBuffer cmd, const RenderGraph& graph);

  gpu::Device& device_;
  // By resource name. Transients are rebuilt when the graph's shape changes; persistent
  // entries survive frames; imported entries point at objects owned elsewhere, for the frame
  // that bound them.
  std::map<std::string, Physical, std::less<>> physical_;
  // Imports are forgotten after each frame (their owner may destroy them); what the frame
  // did to each stays here, by name with the handle it was bound to.
  struct ImportedState {
    uint64_t handle = 0;
    ResourceState state;
  };
  std::map<std::string, ImportedState, std::less<>> importedStates_;
  gpu::Memory transientBlock_;
  std::string transientSignature_;
  std::vector<PhysicalInfo> physicalInfo_;
  std::vector<PassTiming> timings_;
  std::set<std::string, std::less<>> readbackNames_;
  bool readbackAll_ = false;
  struct PendingReadback {
    std::string name;
    VkFormat format;
    VkExtent3D extent;
    gpu::Buffer* staging = nullptr;  // in its frame slot's staging, kept for later frames
  };
  // What one frame in flight holds until it is finished: its timestamps and read-backs.
  // Frame f uses slot f % kMaxFramesInFlight; the staging buffers stay from frame to frame
  // (by resource name, remade only when the size changes).
  struct FrameSlot {
    std::unique_ptr<gpu::TimestampPool> timestamps;
    uint64_t timelineValue = 0;
    std::vector<PendingReadback> pending;
    std::map<std::string, gpu::Buffer, std::less<>> staging;
    std::vector<PhysicalInfo> resources;  // resources() once the frame is finished
  };
  FrameSlot& slotOf(uint64_t frame) { return slots_[frame % gpu::kMaxFramesInFlight]; }
  gpu::Buffer& stagingFor(FrameSlot& slot, const std::string& name, VkDeviceSize bytes);
  std::array<FrameSlot, gpu::kMaxFramesInFlight> slots_;
  std::map<std::string, Readback> readbacks_;
  uint64_t submitted_ = 0;  // frames submitted
  uint64_t finished_ = 0;   // frames finished (collected); frames [finished_, submitted_) are in flight
};

}  // namespace tl::graph
