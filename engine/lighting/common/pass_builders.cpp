#include "lighting/common/pass_builders.h"

#include "graph/executor.h"
#include "lighting/common/history.h"
#include "shared/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>

namespace tl::lighting {

using graph::Usage;

namespace {

VkDescriptorType descriptorType(BindingList::Kind kind) {
  switch (kind) {
    case BindingList::Kind::Uniform: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingList::Kind::BufferIn:
    case BindingList::Kind::BufferOut: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingList::Kind::Sampled: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case BindingList::Kind::Tlas: return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    default: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  }
}

const char* typeName(VkDescriptorType t) {
  switch (t) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "storage buffer";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "sampled image";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "storage image";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return "separate image";
    case VK_DESCRIPTOR_TYPE_SAMPLER: return "separate sampler";
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR: return "acceleration structure";
    default: return "unknown kind";
  }
}

// The graph usage each kind of binding stands for; uniform blocks are host-written buffers
// the graph tracks as storage reads (barriers.h).
Usage usageOf(BindingList::Kind kind) {
  switch (kind) {
    case BindingList::Kind::Uniform:
    case BindingList::Kind::BufferIn:
    case BindingList::Kind::StorageIn: return Usage::StorageRead;
    case BindingList::Kind::Sampled: return Usage::Sampled;
    default: return Usage::StorageWrite;
  }
}

}  // namespace

// ---- BindingList: the list and what it yields ----------------------------------------

void BindingList::entry(uint32_t binding, Kind kind, std::string_view resource, EntryOptions options) {
  Entry e;
  e.binding = binding;
  e.kind = kind;
  e.resource = std::string(resource);
  e.create = std::move(options.create);
  e.sampler = options.sampler;
  e.optional = options.optional;
  e.present = options.present;
  e.mip = options.mip;
  e.update = options.update;
  entries_.push_back(std::move(e));
}

void BindingList::tlasEntry(uint32_t binding, VkAccelerationStructureKHR tlas, const std::vector<std::string>& structures) {
  entry(binding, Kind::Tlas, structures.empty() ? std::string() : structures.front());
  entries_.back().tlas = tlas;
  for (const std::string& s : structures) extraReads_.emplace_back(s, Usage::AccelerationStructureRead);
}

void BindingList::constantEntry(uint32_t binding, const gpu::Image* image, VkImageLayout layout, const gpu::SamplerDesc& sampler,
                                VkBuffer buffer) {
  if (image)
    entry(binding, Kind::Sampled, image->name(), {.sampler = sampler});
  else
    entry(binding, Kind::BufferIn, "(constant buffer)");
  Entry& e = entries_.back();
  e.constant = true;
  e.view = image ? image->view() : VK_NULL_HANDLE;
  e.layout = layout;
  e.buffer = buffer;
}

void BindingList::declareHistory(std::string_view name, const graph::ResourceDesc& desc, graph::RenderGraph& graph,
                                 FrameInputs& in, HistoryKeeper& keeper, const HistoryPolicy& policy) {
  historyValid_ = keepHistory(graph, in, keeper, policy, in.pathName, {{name, desc}}).action != HistoryAction::Restart;
}

void BindingList::setPush(const void* bytes, size_t size) {
  pushBytes_.resize(size);
  std::memcpy(pushBytes_.data(), bytes, size);
  finishPush_ = nullptr;
}

bool BindingList::present(uint32_t binding) const {
  for (const Entry& e : entries_)
    if (e.binding == binding) return e.present;
  return false;
}

std::vector<gpu::Binding> BindingList::layout() const {
  std::map<uint32_t, const Entry*> seen;
  std::vector<gpu::Binding> out;
  for (const Entry& e : entries_) {
    if (auto [it, added] = seen.emplace(e.binding, &e); !added)
      throw PassBuilderError(fmt::format("pass `{}`: binding {} is declared twice (`{}` and `{}`)", name_, e.binding,
                                         it->second->resource, e.resource));
    gpu::Binding b;
    b.binding = e.binding;
    b.type = descriptorType(e.kind);
    b.optional = e.optional;
    out.push_back(b);
  }
  return out;
}

void BindingList::check(const std::vector<gpu::ReflectedBinding>& shader, const std::vector<std::string>& stages) const {
  const std::vector<gpu::Binding> mine = layout();
  for (size_t i = 0; i < shader.size(); ++i) {
    const gpu::ReflectedBinding& r = shader[i];
    const std::string& where = i < stages.size() ? stages[i] : shaderNames_;
    const gpu::Binding* b = nullptr;
    for (const gpu::Binding& x : mine) b = x.binding == r.binding ? &x : b;
    const Entry* e = nullptr;
    for (const Entry& x : entries_) e = x.binding == r.binding ? &x : e;
    if (!b)
      throw PassBuilderError(fmt::format("pass `{}`: shader {} has binding {} (`{}`, {}) which the pass does not declare",
                                         name_, where, r.binding, r.name, typeName(r.type)));
    if (b->type != r.type)
      throw PassBuilderError(fmt::format("pass `{}`: binding {} is `{}` as a {} in the pass but `{}` as a {} in shader {}",
                                         name_, r.binding, e->resource, typeName(b->type), r.name, typeName(r.type), where));
  }
  for (const Entry& e : entries_) {
    bool inShader = false;
    for (const gpu::ReflectedBinding& r : shader) inShader |= r.binding == e.binding;
    if (!inShader)
      throw PassBuilderError(
          fmt::format("pass `{}`: binding {} (`{}`) is not in shader {}", name_, e.binding, e.resource, shaderNames_));
  }
}

std::function<void(graph::PassBuilder&)> BindingList::setup() const {
  return [entries = entries_, extraReads = extraReads_](graph::PassBuilder& b) {
    // One access per resource: a resource bound at two bindings the same way is one read.
    std::set<std::pair<std::string, Usage>> declared;
    for (const Entry& e : entries) {
      if (!e.present || e.constant || e.kind == Kind::Tlas) continue;  // a Tlas's structures are reads()
      const Usage u = usageOf(e.kind);
      if (!declared.emplace(e.resource, u).second) continue;
      if (e.create)
        b.create(e.resource, *e.create, u);
      else if (e.update)
        b.update(e.resource, u);
      else if (e.kind == Kind::StorageInOut || graph::isWrite(u))
        b.write(e.resource, u);
      else
        b.read(e.resource, u);
    }
    for (const auto& [name, usage] : extraReads)
      if (declared.emplace(name, usage).second) b.read(name, usage);
  };
}

std::function<void(graph::PassContext&)> BindingList::bindAndWrite(const gpu::Pipeline& pipeline) const {
  struct Write {
    uint32_t binding;
    Kind kind;
    std::string resource;
    VkSampler sampler;
    VkAccelerationStructureKHR tlas;
    bool constant;
    VkImageView view;
    VkImageLayout layout;
    VkBuffer buffer;
    std::optional<uint32_t> mip;
  };
  std::vector<Write> writes;
  for (const Entry& e : entries_)
    if (e.present)
      writes.push_back({e.binding, e.kind, e.resource, e.kind == Kind::Sampled ? device_.sampler(e.sampler) : VK_NULL_HANDLE,
                        e.tlas, e.constant, e.view, e.layout, e.buffer, e.mip});
  return [&pipeline, writes = std::move(writes), push = pushBytes_, finish = finishPush_](graph::PassContext& ctx) {
    ctx.bind(pipeline);
    if (!push.empty()) {
      std::vector<uint8_t> bytes = push;
      if (finish) finish(ctx, bytes);
      ctx.pushConstantBytes(bytes.data(), uint32_t(bytes.size()));
    }
    gpu::DescriptorWriter& d = ctx.descriptors();
    for (const Write& w : writes) {
      if (w.constant) {
        if (w.kind == Kind::Sampled)
          d.sampledImage(w.binding, w.view, w.sampler, w.layout);
        else
          d.storageBuffer(w.binding, w.buffer);
        continue;
      }
      switch (w.kind) {
        case Kind::Uniform: d.uniformBuffer(w.binding, ctx.buffer(w.resource).handle()); break;
        case Kind::BufferIn:
        case Kind::BufferOut: d.storageBuffer(w.binding, ctx.buffer(w.resource).handle()); break;
        case Kind::Sampled: d.sampledImage(w.binding, ctx.image(w.resource).view(), w.sampler, ctx.layout(w.resource)); break;
        case Kind::Tlas: d.accelerationStructure(w.binding, w.tlas); break;
        default: {
          const gpu::Image& image = ctx.image(w.resource);
          d.storageImage(w.binding, w.mip ? image.mipView(*w.mip) : image.view());
          break;
        }
      }
    }
  };
}

// ---- ComputePass ------------------------------------------------------------------------

ComputePass::ComputePass(gpu::Device& device, std::string name, std::string shader)
    : BindingPass(device, std::move(name), std::move(shader)) {}

ComputePass& ComputePass::dispatch(uint32_t width, uint32_t height, uint32_t depth, uint32_t localX, uint32_t localY,
                                   uint32_t localZ) {
  const uint32_t s[6] = {width, height, depth, localX, localY, localZ};
  std::copy(std::begin(s), std::end(s), size_);
  return *this;
}

ComputePass& ComputePass::record(std::function<void(graph::PassContext&)> fn) {
  record_ = std::move(fn);
  return *this;
}

ComputePass& ComputePass::pipelineName(std::string name) {
  pipelineName_ = std::move(name);
  return *this;
}

graph::PassId ComputePass::add(graph::RenderGraph& graph) {
  gpu::ComputePipelineDesc d;
  d.name = pipelineName_.empty() ? name_ : pipelineName_;
  d.shader = shaderNames_;
  d.layout.bindings = layout();
  d.layout.pushConstantBytes = uint32_t(pushBytes_.size());
  gpu::PipelineCache& cache = device_.pipelines();
  // A new pipeline's list is checked against its shader once, before the pipeline is made.
  if (!cache.contains(d)) check(gpu::reflectSet0(gpu::loadSpirv(shaderNames_)));
  const gpu::Pipeline& pipeline = cache.compute(device_, d);
  std::array<uint32_t, 6> size{size_[0], size_[1], size_[2], size_[3], size_[4], size_[5]};
  auto execute = [prologue = bindAndWrite(pipeline), size, record = record_](graph::PassContext& ctx) {
    prologue(ctx);
    if (record)
      record(ctx);
    else
      ctx.dispatch(size[0], size[1], size[2], size[3], size[4], size[5]);
  };
  return graph.addPass(name_, graph::PassKind::Compute, setup(), std::move(execute));
}

// ---- RayTracingPass ---------------------------------------------------------------------

std::vector<std::string> RayShaders::stages() const {
  std::vector<std::string> all{raygen};
  auto add = [&](const std::string& s) {
    if (!s.empty() && std::find(all.begin(), all.end(), s) == all.end()) all.push_back(s);
  };
  for (const std::string& m : misses) add(m);
  for (const auto& h : hitGroups) add(h.closestHit), add(h.anyHit);
  return all;
}

std::vector<gpu::ReflectedBinding> reflectStages(const std::vector<std::string>& stages, std::vector<std::string>* from) {
  std::vector<gpu::ReflectedBinding> all;
  std::vector<std::string> where;
  for (const std::string& stage : stages)
    for (gpu::ReflectedBinding& r : gpu::reflectSet0(gpu::loadSpirv(stage))) {
      auto same = std::find_if(all.begin(), all.end(), [&](const gpu::ReflectedBinding& x) { return x.binding == r.binding; });
      if (same == all.end()) {
        all.push_back(std::move(r));
        where.push_back(stage);
      } else if (same->type != r.type) {
        throw PassBuilderError(fmt::format("binding {} is `{}` as a {} in shader {} but `{}` as a {} in shader {}", r.binding,
                                           same->name, typeName(same->type), where[size_t(same - all.begin())], r.name,
                                           typeName(r.type), stage));
      }
    }
  if (from) *from = std::move(where);
  return all;
}

namespace {
std::string joined(const std::vector<std::string>& stages) {
  std::string s;
  for (const std::string& x : stages) s += (s.empty() ? "" : ", ") + x;
  return s;
}
}  // namespace

RayTracingPass::RayTracingPass(gpu::Device& device, std::string name, RayShaders shaders)
    : BindingPass(device, std::move(name), joined(shaders.stages())), rayShaders_(std::move(shaders)) {}

RayTracingPass& RayTracingPass::sceneTable(const gpu::DescriptorTable& table) {
  sceneTable_ = &table;
  return *this;
}

RayTracingPass& RayTracingPass::trace(uint32_t width, uint32_t height, uint32_t depth) {
  size_[0] = width, size_[1] = height, size_[2] = depth;
  return *this;
}

graph::PassId RayTracingPass::add(graph::RenderGraph& graph) {
  gpu::RayTracingPipelineDesc d;
  d.name = rayShaders_.name;
  d.raygen = rayShaders_.raygen;
  d.misses = rayShaders_.misses;
  d.hitGroups = rayShaders_.hitGroups;
  d.layout.bindings = layout();
  d.layout.pushConstantBytes = uint32_t(pushBytes_.size());
  if (sceneTable_) d.layout.extraSets = {sceneTable_->layout()};
  gpu::PipelineCache& cache = device_.pipelines();
  // As for compute: a new pipeline's list is checked once, against all its stages together.
  if (!cache.contains(d)) {
    std::vector<std::string> from;
    const std::vector<gpu::ReflectedBinding> shader = reflectStages(rayShaders_.stages(), &from);
    check(shader, from);
  }
  const gpu::Pipeline& pipeline = cache.rayTracing(device_, d);
  auto execute = [prologue = bindAndWrite(pipeline), &pipeline, table = sceneTable_, size = std::array{size_[0], size_[1], size_[2]}](
                     graph::PassContext& ctx) {
    prologue(ctx);
    ctx.flushDescriptors();
    if (table) table->bind(ctx.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline.layout(), shared::kSceneSet);
    // The regions after the bind: a shader reload rebuilds the pipeline (and its table) there.
    ctx.device.ext().cmdTraceRays(ctx.cmd, &pipeline.raygenRegion, &pipeline.missRegion, &pipeline.hitRegion,
                                  &pipeline.callableRegion, size[0], size[1], size[2]);
  };
  return graph.addPass(name_, graph::PassKind::RayTracing, setup(), std::move(execute));
}

}  // namespace tl::lighting

// ---- RasterPass -------------------------------------------------------------------------

namespace tl::lighting {

RasterPass::RasterPass(gpu::Device& device, std::string name, gpu::GraphicsPipelineDesc pipeline)
    : BindingPass(device, std::move(name), pipeline.vertexShader + (pipeline.fragmentShader.empty() ? "" : ", " + pipeline.fragmentShader)) {
  pipelines_.push_back(std::move(pipeline));
}

RasterPass& RasterPass::variant(gpu::GraphicsPipelineDesc pipeline) {
  pipelines_.push_back(std::move(pipeline));
  return *this;
}

RasterPass& RasterPass::colorOut(graph::ImageName image, const graph::ResourceDesc& create, std::optional<glm::vec4> clear) {
  colors_.push_back({std::string(image), create, clear, std::nullopt});
  return *this;
}

RasterPass& RasterPass::depthOut(graph::ImageName image, const graph::ResourceDesc& create, std::optional<float> clear) {
  depth_ = Target{std::string(image), create, std::nullopt, clear};
  return *this;
}

RasterPass& RasterPass::area(uint32_t width, uint32_t height) {
  area_ = VkExtent2D{width, height};
  return *this;
}

RasterPass& RasterPass::sceneTable(const gpu::DescriptorTable& table) {
  sceneTable_ = &table;
  return *this;
}

RasterPass& RasterPass::drawsScene(const gpu::DescriptorTable& table, bool materials, Usage geometry) {
  sceneTable(table);
  // What readSceneInputs reads (frame_inputs.h), as extra reads: the frame constants' read is
  // one access with a uniform binding of them.
  reads(kFrameConstants, Usage::StorageRead);
  reads(kSceneVertices, geometry);
  reads(kSceneIndices, geometry);
  reads(kSceneInstances, Usage::StorageRead);
  if (materials) reads(kSceneMaterials, Usage::StorageRead);
  return *this;
}

RasterPass& RasterPass::draw(Draw fn) {
  draw_ = std::move(fn);
  return *this;
}

graph::PassId RasterPass::add(graph::RenderGraph& graph) {
  gpu::PipelineCache& cache = device_.pipelines();
  std::vector<std::function<void(graph::PassContext&)>> prologues;
  std::vector<const gpu::Pipeline*> pipelines;
  for (gpu::GraphicsPipelineDesc d : pipelines_) {
    d.layout.bindings = layout();
    d.layout.pushConstantBytes = uint32_t(pushBytes_.size());
    d.layout.extraSets.clear();
    if (sceneTable_) d.layout.extraSets = {sceneTable_->layout()};
    d.colorFormats.clear();
    for (const Target& c : colors_) d.colorFormats.push_back(c.create.format);
    d.depthFormat = depth_ ? depth_->create.format : VK_FORMAT_UNDEFINED;
    // As for compute: a new pipeline's list is checked once, against both stages together.
    if (!cache.contains(d)) {
      std::vector<std::string> stages{d.vertexShader};
      if (!d.fragmentShader.empty()) stages.push_back(d.fragmentShader);
      std::vector<std::string> from;
      const std::vector<gpu::ReflectedBinding> shader = reflectStages(stages, &from);
      check(shader, from);
    }
    pipelines.push_back(&cache.graphics(device_, d));
    prologues.push_back(bindAndWrite(*pipelines.back()));
  }

  auto setupList = setup();
  auto setupAll = [setupList, colors = colors_, depth = depth_](graph::PassBuilder& b) {
    setupList(b);
    for (const Target& c : colors) b.create(c.name, c.create, Usage::ColorAttachment);
    if (depth) b.create(depth->name, depth->create, Usage::DepthAttachment);
  };
  auto execute = [prologues = std::move(prologues), pipelines = std::move(pipelines), table = sceneTable_, colors = colors_,
                  depth = depth_, area = area_, draw = draw_](graph::PassContext& ctx) {
    std::vector<graph::Attachment> colorAttachments;
    for (const Target& c : colors) colorAttachments.push_back({c.name, c.clearColor, {}});
    std::optional<graph::Attachment> depthAttachment;
    if (depth) depthAttachment = graph::Attachment{depth->name, {}, depth->clearDepth};
    const Use use = [&](size_t i) {
      prologues[i](ctx);
      ctx.flushDescriptors();
      if (table) table->bind(ctx.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines[i]->layout(), shared::kSceneSet);
    };
    ctx.beginRendering(colorAttachments, depthAttachment, area);
    use(0);
    if (draw) draw(ctx, use);
    ctx.endRendering();
  };
  return graph.addPass(name_, graph::PassKind::Raster, std::move(setupAll), std::move(execute));
}

// ---- TransferPass -----------------------------------------------------------------------

TransferPass& TransferPass::copy(graph::ImageName from, graph::ImageName to) {
  steps_.push_back({Op::Copy, std::string(from), std::string(to), std::nullopt});
  return *this;
}

TransferPass& TransferPass::blit(graph::ImageName from, graph::ImageName to, std::optional<graph::ResourceDesc> create) {
  steps_.push_back({Op::Blit, std::string(from), std::string(to), std::move(create)});
  return *this;
}

TransferPass& TransferPass::clear(graph::ImageName image) {
  steps_.push_back({Op::Clear, {}, std::string(image), std::nullopt});
  return *this;
}

graph::PassId TransferPass::add(graph::RenderGraph& graph) const {
  auto setup = [steps = steps_](graph::PassBuilder& b) {
    for (const Step& s : steps) {
      if (s.op != Op::Clear) b.read(s.from, Usage::TransferSrc);
      if (s.create)
        b.create(s.to, *s.create, Usage::TransferDst);
      else
        b.write(s.to, Usage::TransferDst);
    }
  };
  auto execute = [steps = steps_](graph::PassContext& ctx) {
    for (const Step& s : steps) {
      if (s.op == Op::Copy) gpu::copyImage(ctx.cmd, ctx.image(s.from), ctx.image(s.to));
      if (s.op == Op::Blit) gpu::blitImage(ctx.cmd, ctx.image(s.from), ctx.image(s.to));
      if (s.op == Op::Clear) gpu::clearImage(ctx.cmd, ctx.image(s.to), ctx.layout(s.to));
    }
  };
  return graph.addPass(name_, graph::PassKind::Transfer, setup, std::move(execute));
}

// ---- AccelerationStructurePass ----------------------------------------------------------

AccelerationStructurePass& AccelerationStructurePass::input(graph::BufferName buffer) {
  accesses_.emplace_back(std::string(buffer), Usage::BuildInput);
  return *this;
}

AccelerationStructurePass& AccelerationStructurePass::reads(std::string_view structure) {
  accesses_.emplace_back(std::string(structure), Usage::AccelerationStructureRead);
  return *this;
}

AccelerationStructurePass& AccelerationStructurePass::writes(std::string_view structure) {
  accesses_.emplace_back(std::string(structure), Usage::AccelerationStructureWrite);
  return *this;
}

AccelerationStructurePass& AccelerationStructurePass::scratch(std::string_view name, VkDeviceSize bytes, std::string what) {
  scratch_ = std::string(name);
  scratchDesc_ = graph::ResourceDesc::buffer(bytes, std::move(what));
  return *this;
}

AccelerationStructurePass& AccelerationStructurePass::record(Record fn) {
  record_ = std::move(fn);
  return *this;
}

graph::PassId AccelerationStructurePass::add(graph::RenderGraph& graph) const {
  auto setup = [accesses = accesses_, scratch = scratch_, desc = scratchDesc_](graph::PassBuilder& b) {
    for (const auto& [name, usage] : accesses) {
      if (graph::isWrite(usage))
        b.write(name, usage);
      else
        b.read(name, usage);
    }
    b.create(scratch, desc, Usage::BuildScratch);
  };
  auto execute = [record = record_, scratch = scratch_](graph::PassContext& ctx) { record(ctx, ctx.buffer(scratch)); };
  return graph.addPass(name_, graph::PassKind::AccelerationStructureBuild, setup, std::move(execute));
}

}  // namespace tl::lighting
