#include "lighting/common/pass_builders.h"

#include "graph/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>

namespace tl::lighting {

using graph::Usage;

namespace {

VkDescriptorType descriptorType(ComputePass::Kind kind) {
  switch (kind) {
    case ComputePass::Kind::Uniform: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case ComputePass::Kind::BufferIn:
    case ComputePass::Kind::BufferOut: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case ComputePass::Kind::Sampled: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case ComputePass::Kind::Tlas: return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
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
Usage usageOf(ComputePass::Kind kind) {
  switch (kind) {
    case ComputePass::Kind::Uniform:
    case ComputePass::Kind::BufferIn:
    case ComputePass::Kind::StorageIn: return Usage::StorageRead;
    case ComputePass::Kind::Sampled: return Usage::Sampled;
    default: return Usage::StorageWrite;
  }
}

}  // namespace

ComputePass::ComputePass(gpu::Device& device, std::string name, std::string shader)
    : device_(device), name_(std::move(name)), shader_(std::move(shader)) {}

ComputePass& ComputePass::entry(uint32_t binding, Kind kind, std::string_view resource) {
  Entry e;
  e.binding = binding;
  e.kind = kind;
  e.resource = std::string(resource);
  entries_.push_back(std::move(e));
  return *this;
}

ComputePass& ComputePass::uniform(uint32_t binding, std::string_view buffer) { return entry(binding, Kind::Uniform, buffer); }
ComputePass& ComputePass::bufferIn(uint32_t binding, std::string_view buffer) { return entry(binding, Kind::BufferIn, buffer); }
ComputePass& ComputePass::bufferOut(uint32_t binding, std::string_view buffer) { return entry(binding, Kind::BufferOut, buffer); }
ComputePass& ComputePass::storageIn(uint32_t binding, std::string_view image) { return entry(binding, Kind::StorageIn, image); }
ComputePass& ComputePass::storageOut(uint32_t binding, std::string_view image) { return entry(binding, Kind::StorageOut, image); }
ComputePass& ComputePass::storageInOut(uint32_t binding, std::string_view image) {
  return entry(binding, Kind::StorageInOut, image);
}

ComputePass& ComputePass::storageOut(uint32_t binding, std::string_view image, const graph::ResourceDesc& create) {
  entry(binding, Kind::StorageOut, image);
  entries_.back().create = create;
  return *this;
}

ComputePass& ComputePass::sampled(uint32_t binding, std::string_view image, const gpu::SamplerDesc& sampler) {
  entry(binding, Kind::Sampled, image);
  entries_.back().sampler = sampler;
  return *this;
}

ComputePass& ComputePass::optionalSampled(uint32_t binding, std::string_view image, const graph::RenderGraph& graph,
                                          const gpu::SamplerDesc& sampler) {
  sampled(binding, image, sampler);
  entries_.back().optional = true;
  entries_.back().present = graph.find(image).has_value();
  return *this;
}

ComputePass& ComputePass::history(uint32_t binding, std::string_view name, const graph::ResourceDesc& desc,
                                  graph::RenderGraph& graph, FrameInputs& in, HistoryKeeper& keeper,
                                  const HistoryPolicy& policy, const gpu::SamplerDesc& sampler) {
  const bool stored = in.executor.historyValid(name, desc);
  historyValid_ = keeper.advance(policy, in.key, in.pathName, in.historyLog, {stored}).action != HistoryAction::Restart;
  graph.declarePersistent(name, desc);
  return sampled(binding, name, sampler);
}

ComputePass& ComputePass::optionalSampled(uint32_t binding, std::string_view image, bool present,
                                          const gpu::SamplerDesc& sampler) {
  sampled(binding, image, sampler);
  entries_.back().optional = true;
  entries_.back().present = present;
  return *this;
}

ComputePass& ComputePass::optionalStorageInOut(uint32_t binding, std::string_view image, bool present) {
  storageInOut(binding, image);
  entries_.back().optional = true;
  entries_.back().present = present;
  return *this;
}

bool ComputePass::present(uint32_t binding) const {
  for (const Entry& e : entries_)
    if (e.binding == binding) return e.present;
  return false;
}

ComputePass& ComputePass::accelerationStructure(uint32_t binding, VkAccelerationStructureKHR tlas,
                                                const std::vector<std::string>& structures) {
  entry(binding, Kind::Tlas, structures.empty() ? std::string() : structures.front());
  entries_.back().tlas = tlas;
  for (const std::string& s : structures) reads(s, Usage::AccelerationStructureRead);
  return *this;
}

ComputePass& ComputePass::constantSampled(uint32_t binding, const gpu::Image& image, VkImageLayout layout,
                                          const gpu::SamplerDesc& sampler) {
  sampled(binding, image.name(), sampler);
  entries_.back().constant = true;
  entries_.back().view = image.view();
  entries_.back().layout = layout;
  return *this;
}

ComputePass& ComputePass::constantBuffer(uint32_t binding, VkBuffer buffer) {
  bufferIn(binding, "(constant buffer)");
  entries_.back().constant = true;
  entries_.back().buffer = buffer;
  return *this;
}

ComputePass& ComputePass::reads(std::string_view name, Usage usage) {
  extraReads_.emplace_back(std::string(name), usage);
  return *this;
}

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

std::vector<gpu::Binding> ComputePass::layout() const {
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

void ComputePass::check(const std::vector<gpu::ReflectedBinding>& shader) const {
  const std::vector<gpu::Binding> mine = layout();
  for (const gpu::ReflectedBinding& r : shader) {
    const gpu::Binding* b = nullptr;
    for (const gpu::Binding& x : mine) b = x.binding == r.binding ? &x : b;
    const Entry* e = nullptr;
    for (const Entry& x : entries_) e = x.binding == r.binding ? &x : e;
    if (!b)
      throw PassBuilderError(fmt::format("pass `{}`: shader {} has binding {} (`{}`, {}) which the pass does not declare",
                                         name_, shader_, r.binding, r.name, typeName(r.type)));
    if (b->type != r.type)
      throw PassBuilderError(fmt::format("pass `{}`: binding {} is `{}` as a {} in the pass but `{}` as a {} in shader {}",
                                         name_, r.binding, e->resource, typeName(b->type), r.name, typeName(r.type), shader_));
  }
  for (const Entry& e : entries_) {
    bool inShader = false;
    for (const gpu::ReflectedBinding& r : shader) inShader |= r.binding == e.binding;
    if (!inShader)
      throw PassBuilderError(fmt::format("pass `{}`: binding {} (`{}`) is not in shader {}", name_, e.binding, e.resource, shader_));
  }
}

graph::PassId ComputePass::add(graph::RenderGraph& graph) {
  gpu::ComputePipelineDesc d;
  d.name = name_;
  d.shader = shader_;
  d.layout.bindings = layout();
  d.layout.pushConstantBytes = uint32_t(pushBytes_.size());
  gpu::PipelineCache& cache = device_.pipelines();
  // A new pipeline's list is checked against its shader once, before the pipeline is made.
  if (!cache.contains(d)) check(gpu::reflectSet0(gpu::loadSpirv(shader_)));
  const gpu::Pipeline& pipeline = cache.compute(device_, d);

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
  };
  std::vector<Write> writes;
  for (const Entry& e : entries_)
    if (e.present)
      writes.push_back({e.binding, e.kind, e.resource, e.kind == Kind::Sampled ? device_.sampler(e.sampler) : VK_NULL_HANDLE,
                        e.tlas, e.constant, e.view, e.layout, e.buffer});

  const std::vector<Entry> entries = entries_;
  const auto extraReads = extraReads_;
  auto setup = [&entries, &extraReads](graph::PassBuilder& b) {
    // One access per resource: a resource bound at two bindings the same way is one read.
    std::set<std::pair<std::string, Usage>> declared;
    for (const Entry& e : entries) {
      if (!e.present || e.constant || e.kind == Kind::Tlas) continue;  // a Tlas's structures are reads()
      const Usage u = usageOf(e.kind);
      if (!declared.emplace(e.resource, u).second) continue;
      if (e.create)
        b.create(e.resource, *e.create, u);
      else if (e.kind == Kind::StorageInOut || graph::isWrite(u))
        b.write(e.resource, u);
      else
        b.read(e.resource, u);
    }
    for (const auto& [name, usage] : extraReads)
      if (declared.emplace(name, usage).second) b.read(name, usage);
  };
  std::vector<uint8_t> push = pushBytes_;
  std::array<uint32_t, 6> size{size_[0], size_[1], size_[2], size_[3], size_[4], size_[5]};
  auto execute = [&pipeline, writes = std::move(writes), push = std::move(push), size, record = record_](graph::PassContext& ctx) {
    ctx.bind(pipeline);
    if (!push.empty()) ctx.pushConstantBytes(push.data(), uint32_t(push.size()));
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
        default: d.storageImage(w.binding, ctx.image(w.resource).view()); break;
      }
    }
    if (record)
      record(ctx);
    else
      ctx.dispatch(size[0], size[1], size[2], size[3], size[4], size[5]);
  };
  return graph.addPass(name_, graph::PassKind::Compute, setup, std::move(execute));
}

}  // namespace tl::lighting
