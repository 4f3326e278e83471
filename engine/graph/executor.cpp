#include "graph/executor.h"

#include "gpu/formats.h"

#include <algorithm>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstring>

namespace tl::graph {
namespace {

VkImageUsageFlags imageUsageFor(Usage u) {
  switch (u) {
    case Usage::Sampled: return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Usage::StorageRead: case Usage::StorageWrite: return VK_IMAGE_USAGE_STORAGE_BIT;
    case Usage::ColorAttachment: return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case Usage::DepthAttachment: case Usage::DepthRead: return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    case Usage::TransferSrc: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Usage::TransferDst: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    default: return 0;  // buffer-only usages
  }
}

// Barriers of one point in the command buffer, recorded together in one vkCmdPipelineBarrier2.
class BarrierBatch {
 public:
  void image(const gpu::Image& image, const StageAccess& src, const StageAccess& dst, VkImageLayout oldLayout,
             VkImageLayout newLayout) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src.stages;
    b.srcAccessMask = src.access;
    b.dstStageMask = dst.stages;
    b.dstAccessMask = dst.access;
    b.oldLayout = oldLayout;
    b.newLayout = newLayout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.handle();
    b.subresourceRange = {image.aspect(), 0, image.info().mipLevels, 0, 1};
    images_.push_back(b);
  }
  void buffer(const gpu::Buffer& buffer, const StageAccess& src, const StageAccess& dst) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = src.stages;
    b.srcAccessMask = src.access;
    b.dstStageMask = dst.stages;
    b.dstAccessMask = dst.access;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer.handle();
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    buffers_.push_back(b);
  }
  void record(VkCommandBuffer cmd) {
    if (images_.empty() && buffers_.empty()) return;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = uint32_t(images_.size());
    dep.pImageMemoryBarriers = images_.data();
    dep.bufferMemoryBarrierCount = uint32_t(buffers_.size());
    dep.pBufferMemoryBarriers = buffers_.data();
    vkCmdPipelineBarrier2(cmd, &dep);
    images_.clear();
    buffers_.clear();
  }

 private:
  std::vector<VkImageMemoryBarrier2> images_;
  std::vector<VkBufferMemoryBarrier2> buffers_;
};

const StageAccess kTransferRead{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
// What an owner may do with an imported image once the frame hands it back.
const StageAccess kAnything{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

uint64_t handleOf(const gpu::Image* image, const gpu::Buffer* buffer) {
  return image ? uint64_t(image->handle()) : buffer ? uint64_t(buffer->handle()) : 0;
}

}  // namespace

// ---- PassContext -----------------------------------------------------------------------

bool PassContext::declares(std::string_view name) const {
  for (auto& n : pass_.readNames)
    if (n == name) return true;
  for (auto& n : pass_.writeNames)
    if (n == name) return true;
  return false;
}

const gpu::Image& PassContext::image(std::string_view name) const {
  TL_CHECK(declares(name), "pass `{}` uses `{}`, which it did not declare in setup", pass_.name, name);
  auto& p = executor_.find(name);
  TL_CHECK(p.image, "pass `{}` uses `{}` as an image, but it is a buffer", pass_.name, name);
  return *p.image;
}

const gpu::Buffer& PassContext::buffer(std::string_view name) const {
  TL_CHECK(declares(name), "pass `{}` uses `{}`, which it did not declare in setup", pass_.name, name);
  auto& p = executor_.find(name);
  TL_CHECK(p.buffer, "pass `{}` uses `{}` as a buffer, but it is an image", pass_.name, name);
  return *p.buffer;
}

bool PassContext::historyValid(std::string_view name) const { return executor_.find(name).historyValid; }

VkImageLayout PassContext::layout(std::string_view name) const {
  image(name);  // checks the declaration and the type
  const auto id = graph_.find(name);
  for (const PassAccess& a : compiled_.accesses)
    if (id && a.resource == *id) return a.layout;
  return VK_IMAGE_LAYOUT_UNDEFINED;
}

void PassContext::beginRendering(const std::vector<Attachment>& colors, const std::optional<Attachment>& depth,
                                 std::optional<VkExtent2D> area) {
  std::vector<VkRenderingAttachmentInfo> colorInfos;
  VkExtent3D extent{0, 0, 1};
  for (auto& c : colors) {
    const gpu::Image& img = image(c.name);
    extent = img.extent();
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = img.view();
    a.imageLayout = layout(c.name);
    a.loadOp = c.clearColor ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (c.clearColor) std::memcpy(a.clearValue.color.float32, &c.clearColor->x, sizeof(float) * 4);
    colorInfos.push_back(a);
  }
  VkRenderingAttachmentInfo depthInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  if (depth) {
    const gpu::Image& img = image(depth->name);
    extent = img.extent();
    depthInfo.imageView = img.view();
    depthInfo.imageLayout = layout(depth->name);
    depthInfo.loadOp = depth->clearDepth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depthInfo.clearValue.depthStencil.depth = depth->clearDepth.value_or(0.0f);
  }
  if (area) extent = {area->width, area->height, 1};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {extent.width, extent.height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = uint32_t(colorInfos.size());
  ri.pColorAttachments = colorInfos.data();
  ri.pDepthAttachment = depth ? &depthInfo : nullptr;
  vkCmdBeginRendering(cmd, &ri);
  VkViewport vp{0, 0, float(extent.width), float(extent.height), 0.0f, 1.0f};
  VkRect2D sc{{0, 0}, {extent.width, extent.height}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

void PassContext::setViewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  VkViewport vp{float(x), float(y), float(width), float(height), 0.0f, 1.0f};
  VkRect2D sc{{int32_t(x), int32_t(y)}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

void PassContext::setScissor(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  VkRect2D sc{{int32_t(x), int32_t(y)}, {width, height}};
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

void PassContext::endRendering() { vkCmdEndRendering(cmd); }

void PassContext::bind(const gpu::Pipeline& pipeline) {
  // A shader reload swaps the pass's pipeline in place at its next bind (the passes own
  // their pipelines as non-const members; only this interface is const).
  const_cast<gpu::Pipeline&>(pipeline).refresh();
  vkCmdBindPipeline(cmd, pipeline.bindPoint(), pipeline.handle());
  bound_ = &pipeline;
}

void PassContext::pushConstantBytes(const void* data, uint32_t bytes) {
  TL_CHECK(bound_, "pass `{}` pushes constants with no pipeline bound", pass_.name);
  TL_CHECK(bytes <= bound_->pushConstantBytes(), "pass `{}` pushes {} bytes of constants; pipeline `{}` declares {}",
           pass_.name, bytes, bound_->name(), bound_->pushConstantBytes());
  VkShaderStageFlags stages = bound_->bindPoint() == VK_PIPELINE_BIND_POINT_COMPUTE ? VK_SHADER_STAGE_COMPUTE_BIT
                              : bound_->bindPoint() == VK_PIPELINE_BIND_POINT_GRAPHICS
                                  ? VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT
                                  : VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR |
                                        VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
  vkCmdPushConstants(cmd, bound_->layout(), stages, 0, bytes, data);
}

void PassContext::flushDescriptors() {
  TL_CHECK(bound_, "pass `{}` pushes descriptors with no pipeline bound", pass_.name);
  writer_.push(device, cmd, *bound_);
}

void PassContext::dispatch(uint32_t width, uint32_t height, uint32_t depth, uint32_t localX, uint32_t localY,
                           uint32_t localZ) {
  flushDescriptors();
  vkCmdDispatch(cmd, (width + localX - 1) / localX, (height + localY - 1) / localY, (depth + localZ - 1) / localZ);
}

// ---- Readback --------------------------------------------------------------------------

uint32_t Readback::channels() const { return gpu::formatInfo(format).channels; }

std::vector<float> Readback::texels() const { return gpu::decodeTexels(format, bytes); }

// ---- Executor --------------------------------------------------------------------------

Executor::Executor(gpu::Device& device) : device_(device) {
  for (auto& slot : slots_) slot.timestamps = std::make_unique<gpu::TimestampPool>(device, 256);
}

Executor::~Executor() {
  try {
    finishAll();
  } catch (const std::exception&) {
  }
  device_.waitIdle();
}

Executor::Physical& Executor::find(std::string_view name) {
  auto it = physical_.find(name);
  TL_CHECK(it != physical_.end(), "resource `{}` has no physical resource this frame (was it imported?)", name);
  return it->second;
}

Executor::Physical& Executor::importSlot(std::string_view name) {
  auto& p = physical_[std::string(name)];
  // A name the executor owned until now (a transient or a history of an earlier graph) gives
  // up its own resource: nothing may keep pointing into it.
  if (p.kind != Physical::Kind::Imported) p = Physical{};
  p.kind = Physical::Kind::Imported;
  return p;
}

void Executor::bindImportedImage(std::string_view name, gpu::Image& image, VkImageLayout currentLayout) {
  auto& p = importSlot(name);
  p.image = &image;
  p.buffer = nullptr;
  p.boundLayout = currentLayout;
  auto it = importedStates_.find(name);
  p.state = it != importedStates_.end() && it->second.handle == handleOf(&image, nullptr) ? it->second.state
                                                                                          : ResourceState{};
  p.state.layout = currentLayout;  // the owner's word: the frame before handed it back so
}

void Executor::bindImportedBuffer(std::string_view name, gpu::Buffer& buffer) {
  auto& p = importSlot(name);
  p.buffer = &buffer;
  p.image = nullptr;
  auto it = importedStates_.find(name);
  p.state = it != importedStates_.end() && it->second.handle == handleOf(nullptr, &buffer) ? it->second.state
                                                                                           : ResourceState{};
}

CompiledGraph Executor::compile(const RenderGraph& graph) {
  bindGraphImports(graph);
  return graph.compile(entryStates(graph));
}

void Executor::bindGraphImports(const RenderGraph& graph) {
  for (const auto& decl : graph.resources())
    if (decl.importedBuffer) bindImportedBuffer(decl.name, *decl.importedBuffer);
}

EntryStates Executor::entryStates(const RenderGraph& graph) const {
  EntryStates out;
  for (const auto& decl : graph.resources()) {
    if (!decl.persistent && !decl.imported) continue;
    auto it = physical_.find(decl.name);
    if (it == physical_.end()) continue;
    const Physical& p = it->second;
    if (decl.imported ? p.kind != Physical::Kind::Imported : p.kind != Physical::Kind::Persistent || !(p.desc == decl.desc))
      continue;
    out.emplace(decl.name, p.state);
  }
  return out;
}

VkImageLayout Executor::importedLayout(std::string_view name) const {
  auto it = importedStates_.find(name);
  return it == importedStates_.end() ? VK_IMAGE_LAYOUT_UNDEFINED : it->second.state.layout;
}

const gpu::Image* Executor::image(std::string_view name) const {
  auto it = physical_.find(name);
  return it == physical_.end() ? nullptr : it->second.image;
}

VkImageLayout Executor::layout(std::string_view name) const {
  auto it = physical_.find(name);
  return it == physical_.end() ? VK_IMAGE_LAYOUT_UNDEFINED : it->second.state.layout;
}

void Executor::unbindImported() {
  for (auto it = physical_.begin(); it != physical_.end();)
    it = it->second.kind == Physical::Kind::Imported ? physical_.erase(it) : std::next(it);
}

void Executor::resetHistory() {
  ++historyResets_;
  // The contents go (the next first use discards them); the accesses stay, to be waited for.
  for (auto& [name, p] : physical_)
    if (p.kind == Physical::Kind::Persistent) p.historyValid = false, p.state.layout = VK_IMAGE_LAYOUT_UNDEFINED;
}

bool Executor::historyValid(std::string_view name) const {
  auto it = physical_.find(std::string(name));
  return it != physical_.end() && it->second.historyValid;
}

bool Executor::historyValid(std::string_view name, const ResourceDesc& declared) const {
  auto it = physical_.find(std::string(name));
  return it != physical_.end() && it->second.historyValid && it->second.desc == declared;
}

const Readback& Executor::readback(std::string_view name) const {
  auto it = readbacks_.find(std::string(name));
  TL_CHECK(it != readbacks_.end(), "no read-back of `{}` in the last frame (request it before executing)", name);
  return it->second;
}

void Executor::realise(const RenderGraph& graph, const CompiledGraph& compiled) {
  const auto& decls = graph.resources();
  // An import is bound for the frames that import it: a binding this graph does not import
  // (a reopened capture's image after the capture closed) points at memory its owner may
  // have freed, and would shadow a transient of the same name.
  for (auto it = physical_.begin(); it != physical_.end();) {
    const auto id = graph.find(it->first);
    const bool stale = it->second.kind == Physical::Kind::Imported && !(id && decls[*id].imported);
    it = stale ? physical_.erase(it) : std::next(it);
  }
  // Usage flags of each resource: the union of how the frame uses it, plus sampling and
  // copies so the inspector can always view and read it back.
  std::vector<VkImageUsageFlags> usage(decls.size(), 0);
  for (auto& cp : compiled.order) {
    for (auto& a : cp.reads) usage[a.resource] |= imageUsageFor(a.usage);
    for (auto& a : cp.writes) usage[a.resource] |= imageUsageFor(a.usage);
  }
  // A persistent resource outlives this frame's shape: a pass culled now (an on-demand
  // history's writer) may use it in a later frame, so it gets every declared use.
  for (const auto& pass : graph.passes())
    for (auto [names, usages] : {std::pair{&pass.readNames, &pass.readUsages}, std::pair{&pass.writeNames, &pass.writeUsages}})
      for (size_t i = 0; i < names->size(); ++i)
        if (auto id = graph.find((*names)[i]); id && decls[*id].persistent) usage[*id] |= imageUsageFor((*usages)[i]);

  // Transients: one aliased block, rebuilt only when the graph's shape changes.
  std::vector<ResourceId> transients;
  std::vector<AliasRequest> requests;
  std::string signature;
  for (ResourceId id = 0; id < decls.size(); ++id) {
    const auto& d = decls[id];
    const auto& info = compiled.resources[id];
    if (d.persistent || d.imported || info.culled || info.firstUse == kNone) continue;
    // Transfer source for read-backs, destination so a pass may clear what it creates.
    VkImageUsageFlags u = usage[id] | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (gpu::formatInfo(d.desc.format).kind != gpu::TexelKind::Uint) u |= VK_IMAGE_USAGE_SAMPLED_BIT;
    usage[id] = u;
    transients.push_back(id);
    if (d.desc.type == ResourceType::Image) {
      auto req = gpu::Image::requirements(device_, {d.desc.format, d.desc.extent, d.desc.mipLevels, u});
      requests.push_back({req.size, req.alignment, info.firstUse, info.lastUse});
    } else {
      requests.push_back({0, 1, info.firstUse, info.lastUse});
    }
    signature += fmt::format("{}:{}:{}x{}x{}:{}:{}:{}-{};", d.name, int(d.desc.format), d.desc.extent.width,
                             d.desc.extent.height, d.desc.extent.depth, d.desc.mipLevels, d.desc.size,
                             info.firstUse, info.lastUse);
  }
  AliasPlan plan = planAliasing(requests);

  if (signature != transientSignature_) {
    for (auto it = physical_.begin(); it != physical_.end();)
      it = it->second.kind == Physical::Kind::Transient ? physical_.erase(it) : std::next(it);
    transientBlock_.reset();
    if (plan.totalSize > 0) {
      VkMemoryRequirements block{plan.totalSize, 256, ~0u};
      transientBlock_ = gpu::Memory(device_, block, gpu::MemoryUsage::GpuOnly, "graph.transients");
    }
    for (size_t i = 0; i < transients.size(); ++i) {
      const auto& d = decls[transients[i]];
      Physical p;
      p.desc = d.desc;
      if (d.desc.type == ResourceType::Image) {
        p.ownedImage = gpu::Image(device_, {d.desc.format, d.desc.extent, d.desc.mipLevels, usage[transients[i]]},
                                  transientBlock_.handle(), plan.offsets[i], d.name);
        p.image = nullptr;
      } else {
        p.ownedBuffer = gpu::Buffer(device_, d.desc.size,
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                    gpu::MemoryUsage::GpuOnly, d.name);
      }
      physical_.emplace(d.name, std::move(p));
    }
    transientSignature_ = signature;
  }
  for (auto& [name, p] : physical_) {  // pointers after any map moves
    if (p.kind == Physical::Kind::Imported) continue;
    p.image = p.ownedImage ? &p.ownedImage : nullptr;
    p.buffer = p.ownedBuffer ? &p.ownedBuffer : nullptr;
  }
  // A transient image's first use discards its contents, but its bytes may have held an
  // earlier transient of this frame: that first barrier also waits for those last accesses.
  for (size_t i = 0; i < transients.size(); ++i) {
    Physical& p = physical_.at(decls[transients[i]].name);
    p.state = {};
    p.aliasWait = {};
    const auto& mine = compiled.resources[transients[i]];
    for (size_t j = 0; j < transients.size(); ++j) {
      const auto& other = compiled.resources[transients[j]];
      const bool overlap = plan.offsets[i] < plan.offsets[j] + requests[j].size &&
                           plan.offsets[j] < plan.offsets[i] + requests[i].size;
      if (j == i || !overlap || other.lastUse >= mine.firstUse) continue;
      const StageAccess pending = pendingAccesses(compiled.exit[transients[j]]);
      p.aliasWait.stages |= pending.stages;
      p.aliasWait.access |= pending.access;
    }
  }

  // Persistent resources: created once, recreated (and their history dropped) on change.
  for (ResourceId id = 0; id < decls.size(); ++id) {
    const auto& d = decls[id];
    if (!d.persistent) continue;
    auto it = physical_.find(d.name);
    if (it != physical_.end() && it->second.desc == d.desc) continue;
    Physical p;
    p.kind = Physical::Kind::Persistent;
    p.desc = d.desc;
    VkImageUsageFlags u = usage[id] | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (gpu::formatInfo(d.desc.format).kind != gpu::TexelKind::Uint) u |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (d.desc.type == ResourceType::Image)
      p.ownedImage = gpu::Image(device_, {d.desc.format, d.desc.extent, d.desc.mipLevels, u}, d.name);
    else
      p.ownedBuffer = gpu::Buffer(device_, d.desc.size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, d.name);
    physical_.insert_or_assign(d.name, std::move(p));
    auto& placed = physical_.at(d.name);
    placed.image = placed.ownedImage ? &placed.ownedImage : nullptr;
    placed.buffer = placed.ownedBuffer ? &placed.ownedBuffer : nullptr;
  }

  // What the inspector, captures and the dump show, once this frame is finished.
  FrameSlot& slot = slotOf(submitted_);
  slot.resources.clear();
  for (ResourceId id = 0; id < decls.size(); ++id) {
    const auto& d = decls[id];
    const auto& info = compiled.resources[id];
    if (info.culled || info.firstUse == kNone) continue;
    PhysicalInfo pi;
    pi.name = d.name;
    pi.desc = d.desc;
    pi.writer = info.writer != kNone ? graph.passes()[info.writer].name : (d.imported ? "(imported)" : "(previous frame)");
    pi.firstUse = info.firstUse;
    pi.lastUse = info.lastUse;
    pi.persistent = d.persistent;
    pi.imported = d.imported;
    auto pos = std::find(transients.begin(), transients.end(), id);
    if (pos != transients.end()) {
      size_t i = size_t(pos - transients.begin());
      pi.aliased = d.desc.type == ResourceType::Image;
      pi.offset = plan.offsets[i];
      pi.bytes = requests[i].size ? requests[i].size : d.desc.size;
    } else {
      pi.bytes = approximateBytes(d.desc);
    }
    slot.resources.push_back(pi);
  }
}

void Executor::checkEntry(const RenderGraph& graph, const CompiledGraph& compiled) {
  // The compiled barriers start from the states the graph was compiled against: they must be
  // the ones this executor holds, or the first barriers would name the wrong layouts.
  const auto& decls = graph.resources();
  for (ResourceId id = 0; id < decls.size(); ++id) {
    const auto& d = decls[id];
    if ((!d.persistent && !d.imported) || compiled.resources[id].culled) continue;
    const ResourceState held = carriedOver(find(d.name).state);
    TL_CHECK(compiled.entry[id] == held,
             "`{}` was compiled against another entry state than the executor holds (layout {} vs {}): compile "
             "with graph.compile(executor.entryStates(graph))",
             d.name, layoutName(compiled.entry[id].layout), layoutName(held.layout));
  }
}

void Executor::placeBarriers(VkCommandBuffer cmd, const RenderGraph& graph, const CompiledPass& pass) {
  BarrierBatch batch;
  for (const Barrier& b : pass.barriers) {
    Physical& p = find(graph.resources()[b.resource].name);
    StageAccess src = b.src;
    if (p.kind == Physical::Kind::Transient && b.oldLayout == VK_IMAGE_LAYOUT_UNDEFINED) {
      src.stages |= p.aliasWait.stages;
      src.access |= p.aliasWait.access;
    }
    if (p.image)
      batch.image(*p.image, src, b.dst, b.oldLayout, b.newLayout);
    else if (p.buffer)
      batch.buffer(*p.buffer, src, b.dst);
  }
  batch.record(cmd);
}

gpu::Buffer& Executor::stagingFor(FrameSlot& slot, const std::string& name, VkDeviceSize bytes) {
  gpu::Buffer& b = slot.staging[name];
  if (b.size() != bytes)
    b = gpu::Buffer(device_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback, "readback." + name);
  return b;
}

void Executor::copyForReadback(VkCommandBuffer cmd, FrameSlot& slot, const std::string& name, Physical& p,
                               const PassAccess* writer) {
  ResourceState& state = p.state;
  if (writer) state = ResourceState{writer->layout, PastAccess{writer->scope, kNone}, {}};
  PassAccess copy{kNone, kTransferRead, p.image ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED, false};
  BarrierBatch batch;
  auto place = [&](const std::optional<Barrier>& b) {
    if (!b) return;
    if (p.image)
      batch.image(*p.image, b->src, b->dst, b->oldLayout, b->newLayout);
    else
      batch.buffer(*p.buffer, b->src, b->dst);
    batch.record(cmd);
  };
  place(advance(state, kNone, copy, p.image != nullptr, kNone));

  if (p.image) {
    const gpu::Image& img = *p.image;
    auto fi = gpu::formatInfo(img.format());
    if (fi.bytes == 0) return;
    VkExtent3D e = img.extent();
    VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * e.depth * fi.bytes;
    PendingReadback r{name, img.format(), e, &stagingFor(slot, name, bytes)};
    VkBufferImageCopy region{};
    region.imageSubresource = {img.aspect(), 0, 0, 1};
    region.imageExtent = e;
    vkCmdCopyImageToBuffer(cmd, img.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.staging->handle(), 1, &region);
    slot.pending.push_back(std::move(r));
  } else if (p.buffer) {
    PendingReadback r{name, VK_FORMAT_UNDEFINED, {uint32_t(p.buffer->size()), 1, 1},
                      &stagingFor(slot, name, p.buffer->size())};
    VkBufferCopy region{0, 0, p.buffer->size()};
    vkCmdCopyBuffer(cmd, p.buffer->handle(), r.staging->handle(), 1, &region);
    slot.pending.push_back(std::move(r));
  }
  // Host reads of the staging buffers are ordered by the wait for the frame.

  if (writer) {
    // Back to what the compiled barriers expect after the writer: its layout, and the copy
    // finished before the writer's stages, which the next barrier waits on (so it chains).
    PassAccess back{kNone, writer->scope, writer->layout, false};
    StageAccess src{kTransferRead.stages, 0};
    if (p.image)
      batch.image(*p.image, src, back.scope, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, back.layout);
    else
      batch.buffer(*p.buffer, src, back.scope);
    batch.record(cmd);
  }
}

void Executor::handBackImports(VkCommandBuffer cmd, const RenderGraph& graph) {
  // An imported image leaves the frame in the layout it came in, ready for anything its owner
  // does next; then the executor forgets the import (its owner may destroy it) and keeps what
  // the frame did to it by name and handle.
  BarrierBatch batch;
  for (auto it = physical_.begin(); it != physical_.end();) {
    Physical& p = it->second;
    if (p.kind != Physical::Kind::Imported) {
      ++it;
      continue;
    }
    if (p.image && graph.find(it->first) && p.state.layout != p.boundLayout) {
      PassAccess back{kNone, kAnything, p.boundLayout, false};
      if (auto b = advance(p.state, kNone, back, true, kNone))
        batch.image(*p.image, b->src, b->dst, b->oldLayout, b->newLayout);
    }
    importedStates_[it->first] = ImportedState{handleOf(p.image, p.buffer), p.state};
    it = physical_.erase(it);
  }
  batch.record(cmd);
}

void Executor::execute(const RenderGraph& graph, const CompiledGraph& compiled) {
  submit(graph, compiled);
  finish();
}

void Executor::submit(const RenderGraph& graph, const CompiledGraph& compiled) {
  TL_CHECK(framesInFlight() < gpu::kMaxFramesInFlight,
           "{} frames are already in flight: finish() the oldest before submitting another", framesInFlight());
  bindGraphImports(graph);  // bound already when compiled here; the same binding keeps its state
  for (const std::string& name : graph.readbackRequests()) readbackNames_.insert(name);
  realise(graph, compiled);
  checkEntry(graph, compiled);
  FrameSlot& slot = slotOf(submitted_);
  VkCommandBuffer cmd = device_.beginCommands();
  slot.timestamps->reset(cmd);
  slot.pending.clear();
  // The frame before may still run. Its transients share this frame's memory, and each
  // transient's first barrier here waits only for this frame's earlier users of its bytes:
  // so this frame starts after the one before has finished with everything (persistent and
  // imported resources carry their own accesses across; this orders the rest).
  if (device_.completedValue() < device_.lastSubmittedValue())
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);

  const auto& decls = graph.resources();
  for (const CompiledPass& cp : compiled.order) {
    const PassDecl& decl = graph.passes()[cp.pass];
    device_.beginLabel(cmd, decl.name);
    slot.timestamps->begin(cmd, decl.name);
    placeBarriers(cmd, graph, cp);
    PassContext ctx(device_, *this, graph, decl, cp);
    ctx.cmd = cmd;
    ctx.frameIndex = submitted_;
    if (decl.execute) decl.execute(ctx);
    slot.timestamps->end(cmd);
    device_.endLabel(cmd);
    // A resource's contents are final after its last writer (the steps that update it run
    // before): read back there, before aliasing can reuse the memory. Imports belong to
    // their owners.
    for (const PassAccess& a : cp.accesses) {
      const auto& name = decls[a.resource].name;
      if (!a.writes || decls[a.resource].imported || !(readbackAll_ || readbackNames_.count(name))) continue;
      if (compiled.resources[a.resource].writer != cp.pass) continue;
      copyForReadback(cmd, slot, name, find(name), &a);
    }
  }
  // Every resource now stands where the frame left it.
  for (ResourceId id = 0; id < decls.size(); ++id)
    if (!compiled.resources[id].culled) find(decls[id].name).state = carriedOver(compiled.exit[id]);
  // Persistent resources no pass wrote this frame (history read but not rewritten, a cache
  // that was not rebuilt) hold their last contents: read those back at the end.
  for (auto& [name, p] : physical_) {
    if (p.kind != Physical::Kind::Persistent || !p.historyValid || !graph.find(name)) continue;
    if (p.image && p.state.layout == VK_IMAGE_LAYOUT_UNDEFINED) continue;
    if (!readbackAll_ && !readbackNames_.count(name)) continue;
    const std::string& resource = name;  // clang 14 cannot capture a structured binding
    if (std::any_of(slot.pending.begin(), slot.pending.end(), [&](const PendingReadback& r) { return r.name == resource; }))
      continue;
    copyForReadback(cmd, slot, name, p, nullptr);
  }
  handBackImports(cmd, graph);
  readbackNames_.clear();  // requests made from now on are the next frame's
  readbackAll_ = false;
  slot.timelineValue = device_.submit(cmd);
  ++submitted_;
  // A persistent resource holds something for the frames after this one only if a pass of
  // this frame wrote it; one nobody wrote keeps what it had (nothing, after a reset or a
  // resize). The GPU runs frames in order, so the next frame may read it already.
  for (const auto& cp : compiled.order)
    for (const auto& a : cp.writes)
      if (decls[a.resource].persistent) find(decls[a.resource].name).historyValid = true;
}

bool Executor::frameDone() const {
  return !inFlight() || device_.completedValue() >= slots_[finished_ % gpu::kMaxFramesInFlight].timelineValue;
}

void Executor::finish() {
  if (!inFlight()) return;
  FrameSlot& slot = slotOf(finished_);
  device_.wait(slot.timelineValue);
  const uint64_t frame = finished_++;
  physicalInfo_ = std::move(slot.resources);
  timings_.clear();
  for (auto& s : slot.timestamps->read()) timings_.push_back({s.name, s.milliseconds});
  readbacks_.clear();
  for (const auto& r : slot.pending) {
    Readback out{r.name, r.format, r.extent, std::vector<uint8_t>(r.staging->size()), frame};
    std::memcpy(out.bytes.data(), r.staging->mapped(), out.bytes.size());
    readbacks_[r.name] = std::move(out);
  }
  // Staging for what this frame did not read back goes (a capture's read-back of every
  // buffer is not kept for the frames after it); the rest serves the slot's next frame.
  for (auto it = slot.staging.begin(); it != slot.staging.end();) {
    const bool used = std::any_of(slot.pending.begin(), slot.pending.end(), [&](const PendingReadback& r) { return r.name == it->first; });
    it = used ? std::next(it) : slot.staging.erase(it);
  }
  slot.pending.clear();
}

}  // namespace tl::graph
