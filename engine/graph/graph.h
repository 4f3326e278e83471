// The render graph: passes declare the named resources they read and write (setup), then
// record commands (execute). compile() orders the passes, culls the ones whose outputs
// nobody reads, derives barriers, lifetimes and the aliasing plan, and reports misuse with
// both names. This header and graph.cpp are pure logic (no device): they are unit-tested
// without a GPU. executor.h turns a compiled graph into Vulkan work.
#pragma once

#include "graph/barriers.h"
#include "graph/resource_name.h"

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

// Extents compare member-wise (ResourceDesc's defaulted == needs it; Vulkan has none).
inline bool operator==(const VkExtent3D& a, const VkExtent3D& b) {
  return a.width == b.width && a.height == b.height && a.depth == b.depth;
}

namespace tl::gpu {
class Buffer;
}

namespace tl::graph {

enum class ResourceType : uint8_t { Image, Buffer };

// What a resource looks like. An image with extent.depth > 1 is a 3D image.
struct ResourceDesc {
  ResourceType type = ResourceType::Image;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{1, 1, 1};
  uint32_t mipLevels = 1;
  VkDeviceSize size = 0;    // buffers only, bytes
  std::string description;  // one line, shown by the dump and the inspector
  // How a viewer turns a texel into meaning, declared by whoever writes the resource:
  // "NAME key=resource ..." (lighting/common/decoders.h lists the names). Empty: raw values.
  std::string decoder;
  // Conventional names of the stored channels where they mean something other than colour
  // (e.g. "motion.u motion.v"), declared by the writer; captures name the EXR channels so.
  // Empty: R, G, B, A.
  std::string channels;
  // Display-referred values (tonemapped, sRGB-encoded for a screen), not scene-linear data:
  // captures write such an image as PNG, never as an EXR a reader would take as linear.
  bool display = false;

  static ResourceDesc image2D(VkFormat f, uint32_t w, uint32_t h, std::string what = {}, uint32_t mips = 1);
  static ResourceDesc image3D(VkFormat f, uint32_t w, uint32_t h, uint32_t d, std::string what = {},
                              uint32_t mips = 1);
  static ResourceDesc buffer(VkDeviceSize bytes, std::string what = {});
  ResourceDesc decodedAs(std::string spec) const {
    ResourceDesc d = *this;
    d.decoder = std::move(spec);
    return d;
  }
  ResourceDesc named(std::string channelNames) const {
    ResourceDesc d = *this;
    d.channels = std::move(channelNames);
    return d;
  }
  ResourceDesc displayReferred() const {
    ResourceDesc d = *this;
    d.display = true;
    return d;
  }
  bool operator==(const ResourceDesc&) const = default;
};

// One transient resource's place in aliased memory. Resources whose lifetimes do not
// overlap may share bytes; persistent and imported resources are never aliased.
struct AliasRequest {
  VkDeviceSize size = 0;
  VkDeviceSize alignment = 1;
  uint32_t firstPass = 0;  // inclusive, index into CompiledGraph::order
  uint32_t lastPass = 0;   // inclusive
};
struct AliasPlan {
  std::vector<VkDeviceSize> offsets;  // one per request, aligned
  VkDeviceSize totalSize = 0;         // bytes of the shared block
  VkDeviceSize unaliasedSize = 0;     // what separate allocations would have needed
};
// Greedy first-fit by size: pure, deterministic, unit-tested.
AliasPlan planAliasing(const std::vector<AliasRequest>& requests);

class PassContext;  // executor.h: what execute() gets (command buffer, resource views)

using ExecuteFn = std::function<void(PassContext&)>;

struct PassDecl {
  std::string name;
  PassKind kind = PassKind::Compute;
  std::vector<std::string> readNames;  // resolved at compile
  std::vector<Usage> readUsages;
  std::vector<PassKind> readKinds;
  std::vector<std::string> writeNames;
  std::vector<Usage> writeUsages;
  std::vector<PassKind> writeKinds;
  std::vector<bool> writeUpdates;  // PassBuilder::update: a later step of an earlier pass's write
  bool sideEffect = false;  // never culled (e.g. writes to the swapchain or a file)
  ExecuteFn execute;
};

struct ResourceDecl {
  std::string name;
  ResourceDesc desc;
  bool persistent = false;  // survives across frames (history); never aliased
  bool cache = false;       // persistent, but a frame that writes it does so before its readers
  bool onDemand = false;    // persistent, but writing it does not keep its writer from culling
  bool imported = false;    // owned outside the graph (e.g. scene buffers, swapchain)
  gpu::Buffer* importedBuffer = nullptr;  // importBuffer(): what the executor binds for this frame
  PassId creator = kNone;   // the pass that declared it with create()
};

// Passed to a pass's setup function. Names are checked when the graph is compiled.
class PassBuilder {
 public:
  PassBuilder(class RenderGraph& graph, PassId pass) : graph_(graph), pass_(pass) {}
  // Declares a new transient resource that this pass writes with `usage`.
  void create(std::string_view name, const ResourceDesc& desc, Usage usage);
  // The pass's kind fixes the pipeline stages of each usage. `as` names another kind for work
  // of that kind the pass records besides its own (a compute clear inside a raster pass).
  void read(std::string_view name, Usage usage, std::optional<PassKind> as = std::nullopt);
  void write(std::string_view name, Usage usage, std::optional<PassKind> as = std::nullopt);
  // Writes a resource that a pass declared before this one writes: the next step of work
  // split over passes (the voxels' clear, then each voxelization round; mip m after mip m-1).
  // The steps run in declaration order with the graph's barriers between them, are kept or
  // culled together, and the resource's other readers see the last step (a history's
  // readers, last frame's contents: they run before the first). A second plain write() is
  // misuse, as before.
  void update(std::string_view name, Usage usage, std::optional<PassKind> as = std::nullopt);
  void sideEffect();

 private:
  RenderGraph& graph_;
  PassId pass_;
};

struct CompiledPass {
  PassId pass = kNone;              // index into RenderGraph::passes()
  std::vector<Access> reads;        // resolved
  std::vector<Access> writes;       // resolved
  std::vector<PassAccess> accesses; // one per resource the pass touches, usages merged
  std::vector<Barrier> barriers;    // to place before the pass
};

struct ResourceInfo {
  ResourceId id = kNone;
  PassId writer = kNone;           // the pass whose result readers see (kNone: imported, read only)
  std::vector<PassId> steps;       // every pass that writes it, in order: writer is the last
  std::vector<PassId> readers;
  uint32_t firstUse = kNone;       // index into CompiledGraph::order, inclusive
  uint32_t lastUse = kNone;
  bool culled = false;             // only touched by culled passes
};

struct CompiledGraph {
  std::vector<CompiledPass> order;      // passes that survive culling, in execution order
  std::vector<PassId> culled;           // passes removed because nobody reads their outputs
  std::vector<ResourceInfo> resources;  // indexed by ResourceId
  std::vector<ResourceState> entry;     // indexed by ResourceId: the state assumed on entry
  std::vector<ResourceState> exit;      // indexed by ResourceId: the state the frame leaves
};

// Thrown by compile() for misuse; the message names both sides.
struct GraphError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class RenderGraph {
 public:
  // A resource that outlives one frame (temporal history). It may be read before it is
  // written in a frame (it then holds the previous frame's contents).
  void declarePersistent(std::string_view name, const ResourceDesc& desc);
  // A persistent resource used as a cache: in a frame that rebuilds it the writer runs
  // first and readers see this frame's contents; in a frame with no writer they see the
  // last contents (e.g. voxels rebuilt only when what they hold changes).
  void declareCache(std::string_view name, const ResourceDesc& desc);
  // A persistent resource behind an optional output (a progressive sum nobody reads unless
  // asked): its writer is culled like any other pass when nothing reads its other outputs,
  // and the history simply waits. Plain persistent resources keep their writers alive.
  void declareOnDemandHistory(std::string_view name, const ResourceDesc& desc);
  // A resource owned outside the graph (scene geometry, the swapchain image).
  void declareImported(std::string_view name, const ResourceDesc& desc);
  // An imported buffer together with its owner's buffer: the executor binds it for this
  // frame (a pass or a path imports what it owns through the graph, not the executor).
  void importBuffer(std::string_view name, const ResourceDesc& desc, gpu::Buffer& buffer);
  // Asks for `name` to be read back once this frame is finished (Executor::readbacks()).
  void requestReadback(std::string_view name) { readbackRequests_.emplace_back(name); }
  const std::vector<std::string>& readbackRequests() const { return readbackRequests_; }

  PassId addPass(std::string_view name, PassKind kind,
                 const std::function<void(PassBuilder&)>& setup, ExecuteFn execute);

  // Resources the frame exists to produce; passes feeding them survive culling.
  void markOutput(std::string_view name);

  // Resolves names, orders, culls, derives barriers and lifetimes. Throws GraphError.
  // `entry`: the states persistent and imported resources enter the frame in
  // (Executor::entryStates()); transients always enter fresh.
  CompiledGraph compile(const EntryStates& entry = {}) const;

  // A readable text dump: passes in order with reads/writes/barriers, then resources with
  // format, size, writer and lifetime, then culled passes.
  std::string dump(const CompiledGraph& compiled) const;
  // One barrier in words: "name: src stages [accesses] -> dst stages [accesses], old -> new
  // layout; after `pass`, ...".
  std::string describeBarrier(const Barrier& barrier) const;
  // The same graph as Graphviz DOT (`dot -Tsvg`): passes as boxes, resources as ellipses,
  // an edge from each writer to its resource and from each resource to its readers.
  std::string dot(const CompiledGraph& compiled) const;

  const std::vector<PassDecl>& passes() const { return passes_; }
  const std::vector<ResourceDecl>& resources() const { return resources_; }
  const std::vector<std::string>& outputs() const { return outputs_; }
  std::optional<ResourceId> find(std::string_view name) const;

 private:
  friend class PassBuilder;
  std::vector<PassDecl> passes_;
  std::vector<ResourceDecl> resources_;
  std::vector<std::string> outputs_;
  std::vector<std::string> readbackRequests_;
};

// Human-readable size/format helpers shared by the dump, the CLI and the inspector.
std::string formatName(VkFormat format);
uint32_t formatBytesPerTexel(VkFormat format);
VkDeviceSize approximateBytes(const ResourceDesc& desc);

}  // namespace tl::graph
