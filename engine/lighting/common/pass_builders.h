// Pass builders: a compute pass stated once, binding by binding, over the named-resource graph.
// Each call names a set-0 binding (a constant of shaders/shared/) and the graph resource behind
// it; that one list yields the graph accesses (setup), the push-descriptor layout and the
// pipeline (a device-wide cache, checked against the shader's own bindings), the descriptor
// writes at execute time with the image layouts the graph chose for the usage, and the
// samplers (the device's cache, one per description). What is left to a pass is its push
// constants and its dispatch size:
//
//   ComputePass(in.device, "tonemap", "common/tonemap.comp")
//       .uniform(shared::kTonemapFrame, kFrameConstants)
//       .sampled(shared::kTonemapSource, kCompositeHdr)
//       .storageOut(shared::kTonemapOutput, kTonemapLdr, ldrDesc)
//       .push(push)
//       .dispatch(w, h)
//       .add(graph);
//
// Misuse (a binding declared twice, a binding the shader has and the list lacks or types
// differently) is one error naming the pass, the binding and both sides. RayTracingPass is the
// same list over a ray-tracing pipeline (checked against the union of its stages' bindings),
// with the scene table as set 1 and a trace instead of the dispatch (see below); RasterPass the
// same over a graphics pipeline. The passes without descriptors are lists too: TransferPass
// (copies, blits, clears) and AccelerationStructurePass (builds and refits).
#pragma once

#include "gpu/descriptor_table.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/spirv_reflect.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace tl::lighting {

// The samplers passes use, by what they do (shared by every pass through Device::sampler).
namespace samplers {
inline constexpr gpu::SamplerDesc point{VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, "point.clamp"};
inline constexpr gpu::SamplerDesc linear{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, "linear.clamp"};
inline constexpr gpu::SamplerDesc linearRepeat{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, false, "linear.repeat"};
inline constexpr gpu::SamplerDesc shadowCompare{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, true, "shadow.compare"};
// Outside the map is lit (border white + compare): the sun's fit covers the view.
inline constexpr gpu::SamplerDesc sunShadowCompare{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER, true,
                                                   "shadow.compare.border"};
}  // namespace samplers

// Thrown for a pass whose binding list is wrong; the message names the pass and both sides.
struct PassBuilderError : gpu::Error {
  using gpu::Error::Error;
};

// How a binding-list entry differs from the plain kind (outside BindingList: a default
// argument there needs the complete type).
struct EntryOptions {
  std::optional<graph::ResourceDesc> create;  // the pass creates the resource
  gpu::SamplerDesc sampler{};
  bool optional = false, present = true;
  std::optional<uint32_t> mip;  // a storage image's view of one mip level
  bool update = false;          // the next step of an earlier pass's write (graph::PassBuilder::update)
};

// What every pass builder shares: the set-0 binding list and what it yields (the graph
// accesses, the push-descriptor layout, its check against the shaders, the descriptor writes)
// and the push constants. ComputePass and RayTracingPass add their pipeline and their work.
class BindingList {
 public:
  enum class Kind : uint8_t { Uniform, BufferIn, BufferOut, Sampled, StorageIn, StorageOut, StorageInOut, Tlas };
  struct Entry {
    uint32_t binding = 0;
    Kind kind = Kind::Sampled;
    std::string resource;
    std::optional<graph::ResourceDesc> create;
    gpu::SamplerDesc sampler{};
    VkAccelerationStructureKHR tlas = VK_NULL_HANDLE;
    bool optional = false, present = true;
    std::optional<uint32_t> mip;
    bool update = false;
    bool constant = false;  // outside the graph: `view` (with `layout`) or `buffer`
    VkImageView view = VK_NULL_HANDLE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkBuffer buffer = VK_NULL_HANDLE;
  };

  const std::string& name() const { return name_; }
  bool historyValid() const { return historyValid_; }
  bool present(uint32_t binding) const;
  // The layout the list yields (what the pipeline is built with), for tests and the docs.
  std::vector<gpu::Binding> layout() const;
  // Checks the list against the set-0 bindings of the pipeline's shaders (gpu/spirv_reflect.h;
  // for several stages, their union: reflectStages); `stages[i]` names the shader that
  // declares `shader[i]` (empty: the pass's shader). Throws PassBuilderError.
  void check(const std::vector<gpu::ReflectedBinding>& shader, const std::vector<std::string>& stages = {}) const;

 protected:
  BindingList(gpu::Device& device, std::string name, std::string shaders)
      : device_(device), name_(std::move(name)), shaderNames_(std::move(shaders)) {}

  void entry(uint32_t binding, Kind kind, std::string_view resource, EntryOptions options = {});
  void tlasEntry(uint32_t binding, VkAccelerationStructureKHR tlas, const std::vector<std::string>& structures);
  // Outside the graph: a sampled `image` in `layout`, or (image null) a storage `buffer`.
  void constantEntry(uint32_t binding, const gpu::Image* image, VkImageLayout layout, const gpu::SamplerDesc& sampler,
                     VkBuffer buffer);
  void declareHistory(std::string_view name, const graph::ResourceDesc& desc, graph::RenderGraph& graph, FrameInputs& in,
                      HistoryKeeper& keeper, const HistoryPolicy& policy);
  void setPush(const void* bytes, size_t size);

  // The graph accesses of the list (the setup of graph::RenderGraph::addPass).
  std::function<void(graph::PassBuilder&)> setup() const;
  // What execute does before the work: binds `pipeline`, pushes the constants (finished for
  // this frame) and writes the descriptors; the work's draw, dispatch or trace flushes them.
  std::function<void(graph::PassContext&)> bindAndWrite(const gpu::Pipeline& pipeline) const;

  gpu::Device& device_;
  std::string name_;
  std::string shaderNames_;  // the shader, or the stages, as messages name them
  std::vector<Entry> entries_;
  std::vector<std::pair<std::string, graph::Usage>> extraReads_;
  std::vector<uint8_t> pushBytes_;
  std::function<void(graph::PassContext&, std::vector<uint8_t>&)> finishPush_;
  bool historyValid_ = false;
};

// The fluent list, returning the pass (`Self`) so a declaration reads as one statement.
template <class Self>
class BindingPass : public BindingList {
 public:
  // Buffers: a uniform block (the frame constants), storage read, storage written (an existing
  // buffer, or one this pass creates with `create`).
  Self& uniform(uint32_t binding, graph::BufferName buffer) { return listed(binding, Kind::Uniform, buffer); }
  Self& bufferIn(uint32_t binding, graph::BufferName buffer) { return listed(binding, Kind::BufferIn, buffer); }
  Self& bufferOut(uint32_t binding, graph::BufferName buffer) { return listed(binding, Kind::BufferOut, buffer); }
  Self& bufferOut(uint32_t binding, graph::BufferName buffer, const graph::ResourceDesc& create) {
    return listed(binding, Kind::BufferOut, buffer, {.create = create});
  }
  // A storage buffer a pass declared before this one writes, written again as the next step of
  // that work (graph::PassBuilder::update), as storageUpdate for an image.
  Self& bufferUpdate(uint32_t binding, graph::BufferName buffer) {
    return listed(binding, Kind::BufferOut, buffer, {.update = true});
  }
  // A storage buffer read that the frame may lack (the light table in a scene without lights):
  // absent, no access and no descriptor (partially bound; the shader is told, e.g. by a count).
  Self& optionalBufferIn(uint32_t binding, graph::BufferName buffer, bool present) {
    return listed(binding, Kind::BufferIn, buffer, {.optional = true, .present = present});
  }
  // Images: sampled, storage read, storage written (an existing resource, or one this pass
  // creates with `create`), storage read and written in place.
  Self& sampled(uint32_t binding, graph::ImageName image, const gpu::SamplerDesc& sampler = samplers::point) {
    return listed(binding, Kind::Sampled, image, {.sampler = sampler});
  }
  Self& storageIn(uint32_t binding, graph::ImageName image) { return listed(binding, Kind::StorageIn, image); }
  Self& storageOut(uint32_t binding, graph::ImageName image) { return listed(binding, Kind::StorageOut, image); }
  Self& storageOut(uint32_t binding, graph::ImageName image, const graph::ResourceDesc& create) {
    return listed(binding, Kind::StorageOut, image, {.create = create});
  }
  Self& storageInOut(uint32_t binding, graph::ImageName image) { return listed(binding, Kind::StorageInOut, image); }
  // A storage image a pass declared before this one writes, read and written in place as the
  // next step of that work (graph::PassBuilder::update): the voxels' clear, then each
  // voxelization round. The graph orders the steps and places the barriers between them.
  Self& storageUpdate(uint32_t binding, graph::ImageName image) {
    return listed(binding, Kind::StorageInOut, image, {.update = true});
  }
  // One mip level of a storage image (its view of that level), for a chain that makes a level
  // per pass from the one before: the first pass writes its level with storageOut, each next
  // reads the last level with storageIn and writes its own with storageUpdate.
  Self& storageIn(uint32_t binding, graph::ImageName image, uint32_t mip) {
    return listed(binding, Kind::StorageIn, image, {.mip = mip});
  }
  Self& storageOut(uint32_t binding, graph::ImageName image, uint32_t mip) {
    return listed(binding, Kind::StorageOut, image, {.mip = mip});
  }
  // The first level of such a chain, creating the image (all its mips) with `create`.
  Self& storageOut(uint32_t binding, graph::ImageName image, const graph::ResourceDesc& create, uint32_t mip) {
    return listed(binding, Kind::StorageOut, image, {.create = create, .mip = mip});
  }
  Self& storageUpdate(uint32_t binding, graph::ImageName image, uint32_t mip) {
    return listed(binding, Kind::StorageInOut, image, {.mip = mip, .update = true});
  }
  // A sampled input that may be absent from this frame's graph (nobody wrote it): then there
  // is no access and no descriptor (the binding is partially bound, no stand-in resource);
  // present() says which, for the push constant that tells the shader.
  Self& optionalSampled(uint32_t binding, graph::ImageName image, const graph::RenderGraph& graph,
                        const gpu::SamplerDesc& sampler = samplers::point) {
    return optionalSampled(binding, image, graph.find(image).has_value(), sampler);
  }
  // The same where the pass knows whether the input exists (a path's optional output).
  Self& optionalSampled(uint32_t binding, graph::ImageName image, bool present,
                        const gpu::SamplerDesc& sampler = samplers::point) {
    return listed(binding, Kind::Sampled, image, {.sampler = sampler, .optional = true, .present = present});
  }
  // Last frame's `name` (declared persistent here) sampled at `binding`. Whether it holds
  // anything is the history's decision from the frame key (frame_key.h): historyValid().
  Self& history(uint32_t binding, graph::ImageName name, const graph::ResourceDesc& desc, graph::RenderGraph& graph,
                FrameInputs& in, HistoryKeeper& keeper, const HistoryPolicy& policy,
                const gpu::SamplerDesc& sampler = samplers::linear) {
    declareHistory(name, desc, graph, in, keeper, policy);
    return sampled(binding, name, sampler);
  }
  // A storage image read and written in place that the pass may leave unbound (an accumulation
  // the frame does not keep): absent, no access and no descriptor, as for optionalSampled.
  Self& optionalStorageInOut(uint32_t binding, graph::ImageName image, bool present) {
    return listed(binding, Kind::StorageInOut, image, {.optional = true, .present = present});
  }

  // A top level traced by ray queries or rays: its handle, and the graph structures it stands
  // for (read as acceleration structures: the top level and the bottom levels it refers to).
  Self& accelerationStructure(uint32_t binding, VkAccelerationStructureKHR tlas, const std::vector<std::string>& structures) {
    tlasEntry(binding, tlas, structures);
    return self();
  }
  // Made outside the frame and never written in it (the rt path's blue noise, uploaded once;
  // the scene's instance data, written at load): bound as they are, with no graph access.
  Self& constantSampled(uint32_t binding, const gpu::Image& image, VkImageLayout layout,
                        const gpu::SamplerDesc& sampler = samplers::point) {
    constantEntry(binding, &image, layout, sampler, VK_NULL_HANDLE);
    return self();
  }
  Self& constantBuffer(uint32_t binding, VkBuffer buffer) {
    constantEntry(binding, nullptr, VK_IMAGE_LAYOUT_UNDEFINED, {}, buffer);
    return self();
  }
  // A resource the pass reads or writes without a set-0 binding (e.g. through another set).
  Self& reads(std::string_view name, graph::Usage usage) {
    extraReads_.emplace_back(std::string(name), usage);
    return self();
  }

  template <class T>
  Self& push(const T& constants) {
    setPush(&constants, sizeof(T));
    return self();
  }
  // Constants finished when the pass records, from what only the frame knows then (whether a
  // history holds anything: PassContext::historyValid); `finish` runs at every record.
  template <class T>
  Self& push(const T& constants, std::type_identity_t<std::function<void(graph::PassContext&, T&)>> finish) {
    push(constants);
    finishPush_ = [finish = std::move(finish)](graph::PassContext& ctx, std::vector<uint8_t>& bytes) {
      T t;
      std::memcpy(&t, bytes.data(), sizeof(T));
      finish(ctx, t);
      std::memcpy(bytes.data(), &t, sizeof(T));
    };
    return self();
  }

 protected:
  using BindingList::BindingList;
  Self& self() { return static_cast<Self&>(*this); }
  Self& listed(uint32_t binding, Kind kind, std::string_view resource, EntryOptions options = {}) {
    entry(binding, kind, resource, std::move(options));
    return self();
  }
};

class ComputePass final : public BindingPass<ComputePass> {
 public:
  ComputePass(gpu::Device& device, std::string name, std::string shader);

  ComputePass& dispatch(uint32_t width, uint32_t height, uint32_t depth = 1, uint32_t localX = 8, uint32_t localY = 8,
                        uint32_t localZ = 1);
  // Instead of one dispatch: records with the pipeline bound and the descriptors pending.
  ComputePass& record(std::function<void(graph::PassContext&)> fn);
  // Passes that run one shader over one list share a pipeline by this name (the voxel mips, a
  // pass per level); by default a pass names its own.
  ComputePass& pipelineName(std::string name);

  // Checks the list, gets the pipeline and adds the pass. Throws PassBuilderError.
  graph::PassId add(graph::RenderGraph& graph);

 private:
  uint32_t size_[6] = {1, 1, 1, 8, 8, 1};
  std::function<void(graph::PassContext&)> record_;
  std::string pipelineName_;
};

// A ray-tracing pipeline's shaders: gpu::RayTracingPipelineDesc less its layout, which the
// binding list gives. `name` names the pipeline: passes that trace the same shaders with the
// same list share one (rt.trace and rt.trace.2, rt.rawRays and rt.rawRays.pending).
struct RayShaders {
  std::string name;
  std::string raygen;
  std::vector<std::string> misses;
  std::vector<gpu::RayTracingPipelineDesc::HitGroup> hitGroups;
  // Every stage's shader, in the pipeline's order (raygen, misses, hit groups), once each.
  std::vector<std::string> stages() const;
};

// The set-0 bindings of several stages, each once: what a pipeline of them must be given.
// `from[i]` is the stage that declares result[i] (the first that does). A binding two stages
// declare with different types throws PassBuilderError.
std::vector<gpu::ReflectedBinding> reflectStages(const std::vector<std::string>& stages, std::vector<std::string>* from = nullptr);

// A ray-tracing pass stated as a binding list, like ComputePass, plus its shaders, the scene's
// descriptor table as set 1 (the any-hit shaders read the materials through it) and the trace
// size. Its pipeline comes from the device's cache (gpu::PipelineCache), keyed by the shaders
// and the layout, so a new scene-table layout is a new pipeline and an unchanged one is reused
// across scenes (seconds to minutes of compilation on lavapipe).
//
//   RayTracingPass(in.device, "rt.trace", kTraceShaders)
//       .uniform(shared::kRtBindingFrame, kFrameConstants)
//       .accelerationStructure(shared::kRtBindingTlas, structures.tlas, structures.names)
//       .storageOut(shared::kRtBindingHitsOut, kHits, hitsDesc)
//       .sceneTable(in.scene.table())
//       .push(push)
//       .trace(w, h)
//       .add(graph);
class RayTracingPass final : public BindingPass<RayTracingPass> {
 public:
  RayTracingPass(gpu::Device& device, std::string name, RayShaders shaders);

  // The scene's descriptor table, bound as set shared::kSceneSet beside the pushed set 0.
  RayTracingPass& sceneTable(const gpu::DescriptorTable& table);
  // One ray generation per (x, y, z).
  RayTracingPass& trace(uint32_t width, uint32_t height, uint32_t depth = 1);

  // Checks the list against every stage, gets the pipeline and adds the pass. Throws
  // PassBuilderError.
  graph::PassId add(graph::RenderGraph& graph);

 private:
  RayShaders rayShaders_;
  const gpu::DescriptorTable* sceneTable_ = nullptr;
  uint32_t size_[3] = {1, 1, 1};
};

// A raster pass stated as a binding list, like ComputePass: its pipeline (shaders, vertex
// input, raster state: a gpu::GraphicsPipelineDesc whose layout and attachment formats the
// pass fills in), its attachments as graph resources it creates with their clear values, the
// scene's descriptor table as set 1 where it draws the scene (which also reads the scene's
// buffers), and a draw callback that records the draws with the pipeline bound, the constants
// pushed and the descriptors and the scene table bound. A pass that draws with several
// pipelines over one list (opaque and alpha-masked casters) names the others with variant();
// the callback's `use(i)` binds variant i the same way (0 is bound before the callback runs).
// Each variant's list is checked against the union of its vertex and fragment bindings.
//
//   RasterPass(in.device, "gbuffer", gbufferPipeline)
//       .uniform(shared::kBindingFrame, kFrameConstants)
//       .colorOut(kGbufferNormal, normalDesc, glm::vec4(0.0f))
//       .depthOut(gbuffer::kDepth, depthDesc, 0.0f)
//       .drawsScene(in.scene.table())
//       .draw([&in](graph::PassContext& ctx, const RasterPass::Use&) { in.scene.drawAll(ctx); })
//       .add(graph);
class RasterPass final : public BindingPass<RasterPass> {
 public:
  using Use = std::function<void(size_t variant)>;
  using Draw = std::function<void(graph::PassContext&, const Use&)>;

  // `pipeline`'s layout and attachment formats are ignored: the list and the attachments give them.
  RasterPass(gpu::Device& device, std::string name, gpu::GraphicsPipelineDesc pipeline);

  // Another pipeline drawn with the same list (its layout and formats, too, come from the pass).
  RasterPass& variant(gpu::GraphicsPipelineDesc pipeline);
  // A colour or depth attachment the pass creates (`create`), cleared to `clear` (none: loaded).
  RasterPass& colorOut(graph::ImageName image, const graph::ResourceDesc& create, std::optional<glm::vec4> clear);
  RasterPass& depthOut(graph::ImageName image, const graph::ResourceDesc& create, std::optional<float> clear);
  // The rendering area of a pass without attachments (one that writes storage images only).
  RasterPass& area(uint32_t width, uint32_t height);
  // The scene's descriptor table as set shared::kSceneSet, and the scene's buffers the draws
  // read (frame_inputs.h readSceneInputs; `materials`: the material table too; `geometry`: how
  // the vertices and indices are read, as vertex input or, fetched by the shader, as storage).
  RasterPass& drawsScene(const gpu::DescriptorTable& table, bool materials = true,
                         graph::Usage geometry = graph::Usage::VertexOrIndex);
  // The scene table alone, for a pass outside the frame (the albedo baker: no frame
  // constants), which states the buffers its draws read with reads().
  RasterPass& sceneTable(const gpu::DescriptorTable& table);
  RasterPass& draw(Draw fn);

  // Checks each pipeline's list against its stages, gets the pipelines and adds the pass.
  // Throws PassBuilderError.
  graph::PassId add(graph::RenderGraph& graph);

 private:
  struct Target {
    std::string name;
    graph::ResourceDesc create;
    std::optional<glm::vec4> clearColor;
    std::optional<float> clearDepth;
  };
  std::vector<gpu::GraphicsPipelineDesc> pipelines_;
  std::vector<Target> colors_;
  std::optional<Target> depth_;
  std::optional<VkExtent2D> area_;
  const gpu::DescriptorTable* sceneTable_ = nullptr;
  Draw draw_;
};

// A transfer pass stated as one list: copies (same size and format), blits (converting the
// format) and clears, from which the graph accesses follow. How paths keep this frame's results
// as next frame's history (addCopyPass, copy_pass.h), the composite passes a path's whole image
// through and a rebuilt cache starts empty.
//
//   TransferPass("composite").blit(path.radiance, kCompositeHdr, hdrDesc).add(graph);
class TransferPass {
 public:
  explicit TransferPass(std::string name) : name_(std::move(name)) {}
  TransferPass& copy(graph::ImageName from, graph::ImageName to);
  // Into `to`, which this pass creates with `create` where given.
  TransferPass& blit(graph::ImageName from, graph::ImageName to, std::optional<graph::ResourceDesc> create = std::nullopt);
  // Mip 0 to zero.
  TransferPass& clear(graph::ImageName image);
  graph::PassId add(graph::RenderGraph& graph) const;

 private:
  enum class Op : uint8_t { Copy, Blit, Clear };
  struct Step {
    Op op;
    std::string from, to;  // a clear has only `to`
    std::optional<graph::ResourceDesc> create;
  };
  std::string name_;
  std::vector<Step> steps_;
};

// An acceleration-structure build or refit stated as one list: the buffers it builds from
// (vertices and indices, a top level's instances), the structures it reads (the bottom levels
// a top level refers to; a refit reads what it rewrites), the one it writes, and its scratch,
// which the pass creates and hands to the recording.
//
//   AccelerationStructurePass(names.tlasPass)
//       .input(names.tlasInstances)
//       .writes(names.tlas)
//       .scratch(names.tlasScratch, topLevel.scratchBytes(), "scratch of the top-level build")
//       .record([this](graph::PassContext& ctx, const gpu::Buffer& scratch) { topLevel.record(ctx.cmd, scratch); })
//       .add(graph);
class AccelerationStructurePass {
 public:
  using Record = std::function<void(graph::PassContext&, const gpu::Buffer& scratch)>;

  explicit AccelerationStructurePass(std::string name) : name_(std::move(name)) {}
  AccelerationStructurePass& input(graph::BufferName buffer);
  AccelerationStructurePass& reads(std::string_view structure);
  AccelerationStructurePass& writes(std::string_view structure);
  AccelerationStructurePass& scratch(std::string_view name, VkDeviceSize bytes, std::string what);
  AccelerationStructurePass& record(Record fn);
  graph::PassId add(graph::RenderGraph& graph) const;

 private:
  std::string name_;
  std::vector<std::pair<std::string, graph::Usage>> accesses_;  // reads and the write
  std::string scratch_;
  graph::ResourceDesc scratchDesc_;
  Record record_;
};

}  // namespace tl::lighting
