// The render graph's barrier model, pure logic (no device): the usages a pass declares, the
// pipeline stages, accesses and image layouts each usage means in each kind of pass, and the
// per-resource state from which every barrier is derived. graph.cpp runs it over a frame; the
// executor places what it derives and carries the states across frames. Unit-tested without a GPU.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tl::graph {

using ResourceId = uint32_t;
using PassId = uint32_t;
inline constexpr uint32_t kNone = ~0u;

// The kind of work a pass records; with a Usage it fixes the pipeline stages of an access.
enum class PassKind : uint8_t {
  Raster,                         // draws: vertex input, vertex and fragment shaders, attachments
  Compute,                        // dispatches (ray queries included)
  RayTracing,                     // traceRays: the ray-tracing shader stages
  Transfer,                       // copies, clears, blits
  AccelerationStructureBuild,     // acceleration-structure builds and refits
};
const char* kindName(PassKind k);

// How a pass touches a resource. Reads and writes are separate values so a pass that
// reads and writes one resource (read-modify-write, history) declares both.
enum class Usage : uint8_t {
  Sampled,                    // read: sampled image / uniform texel
  StorageRead,                // read: storage image or storage buffer (or a host-written uniform buffer)
  DepthRead,                  // read: depth attachment, test only
  TransferSrc,                // read: copy source
  VertexOrIndex,              // read: vertex / index buffer
  BuildInput,                 // read: vertices, indices or instances an acceleration-structure build reads
  AccelerationStructureRead,  // read: a structure traced (ray tracing, ray query) or read by a build
                              // (a top level's bottom levels, a refit's source)
  StorageWrite,               // write: storage image or storage buffer
  ColorAttachment,            // write: colour attachment
  DepthAttachment,            // write: depth attachment
  TransferDst,                // write: copy destination / clear
  BuildScratch,               // write: an acceleration-structure build's scratch memory
  AccelerationStructureWrite, // write: the structure a build or refit writes
};
bool isWrite(Usage u);
const char* usageName(Usage u);

struct Access {
  ResourceId resource = kNone;
  Usage usage = Usage::Sampled;
  PassKind kind = PassKind::Compute;  // whose stages: the pass's kind, or the one given for the access
};

// A set of pipeline stages and the memory accesses they make: one side of a barrier.
struct StageAccess {
  VkPipelineStageFlags2 stages = 0;
  VkAccessFlags2 access = 0;
  bool operator==(const StageAccess&) const = default;
};

// What one pass does to one resource: all its declared usages merged (a read-modify-write is
// one access with both), and the layout an image must be in for it.
struct PassAccess {
  ResourceId resource = kNone;
  StageAccess scope;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // UNDEFINED for buffers
  bool writes = false;
};

// The whole barrier vocabulary of the engine: a usage in a kind of pass fixes the stages, the
// accesses and the image layout. False for a usage the kind cannot make (a sampled read in a
// transfer pass); compile() turns that into a GraphError naming the pass and the resource.
bool accessFor(Usage usage, PassKind kind, StageAccess& scope, VkImageLayout& layout);

// One access already made to a resource, and by which pass (kNone: before this frame, by the
// previous frame or by the resource's owner).
struct PastAccess {
  StageAccess scope;
  PassId pass = kNone;
  bool operator==(const PastAccess&) const = default;
};

// What the barrier model knows about one resource between two accesses: its layout, its last
// write, and every read since that write (each already synchronised with it). A barrier is
// derived from this state and the next access alone:
// - a read waits for the last write, once per (stage, access) combination;
// - a write, or a layout transition (which writes the image), waits for the last write and
//   for every read since it;
// - after a layout transition the transition itself counts as part of the last write, at the
//   stages it was made visible to, so later readers elsewhere chain onto it.
struct ResourceState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  std::optional<PastAccess> write;
  std::vector<PastAccess> reads;
  bool operator==(const ResourceState&) const = default;
};

// A dependency the executor must place before a pass: `src` must finish (and its writes be
// made available) before `dst` starts (and sees them). Images also change layout; an old
// layout of UNDEFINED discards the contents (a transient's first use in the frame).
struct Barrier {
  ResourceId resource = kNone;
  StageAccess src;
  StageAccess dst;
  VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageLayout newLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  std::vector<PassId> waitsFor;  // passes whose accesses `src` covers; kNone: before this frame
  bool transition() const { return oldLayout != newLayout; }
};

// Advances `state` by one access of pass `pass` and returns the barrier that must come first,
// if any. `image`: layouts matter. Pure; the graph and the executor (read-backs) share it.
std::optional<Barrier> advance(ResourceState& state, ResourceId resource, const PassAccess& access, bool image,
                               PassId pass);

// What a later write, layout transition or reuse of the memory must wait for: the last
// write's stages and writes, and the stages of every read since.
StageAccess pendingAccesses(const ResourceState& state);

// The state as the next frame sees it: every access it remembers happened before that frame
// (pass kNone), duplicates merged.
ResourceState carriedOver(const ResourceState& state);

// The state each persistent or imported resource enters a frame in, by name (what the
// executor carried over from the previous frame). Missing names enter fresh: UNDEFINED, no
// pending access (a new image, or a buffer only the host has written).
using EntryStates = std::map<std::string, ResourceState, std::less<>>;

// Readable names for the dump: "compute", "storage write", "GENERAL".
std::string stageNames(VkPipelineStageFlags2 stages);
std::string accessNames(VkAccessFlags2 access);
const char* layoutName(VkImageLayout layout);

}  // namespace tl::graph
