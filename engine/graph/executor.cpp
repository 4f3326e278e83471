#include "graph/executor.h"

#include "gpu/formats.h"

#include <algorithm>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstring>

namespace tl::graph {
namespace {

struct State {
  VkPipelineStageFlags2 stage;
  VkAccessFlags2 access;
  VkImageLayout layout;
};

VkPipelineStageFlags2 shaderStage(PassKind kind) {
  switch (kind) {
    case PassKind::Raster: return VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case PassKind::Compute: return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    case PassKind::RayTracing: return VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
    case PassKind::Transfer: return VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  }
  return VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
}

// The whole barrier vocabulary of the engine: a usage in a kind of pass fixes the stage,
// the access and the image layout.
State stateFor(Usage usage, PassKind kind) {
  switch (usage) {
    case Usage::Sampled: return {shaderStage(kind), VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL};
    case Usage::StorageRead: return {shaderStage(kind), VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL};
    case Usage::StorageWrite:
      return {shaderStage(kind), VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
              VK_IMAGE_LAYOUT_GENERAL};
    case Usage::ColorAttachment:
      return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    case Usage::DepthAttachment:
      return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
    case Usage::DepthRead:
      return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL};
    case Usage::TransferSrc:
      return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    case Usage::TransferDst:
      return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    case Usage::VertexOrIndex:
      return {VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT,
              VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  return {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
          VK_IMAGE_LAYOUT_GENERAL};
}

VkImageUsageFlags imageUsageFor(Usage u) {
  switch (u) {
    case Usage::Sampled: return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Usage::StorageRead: case Usage::StorageWrite: return VK_IMAGE_USAGE_STORAGE_BIT;
    case Usage::ColorAttachment: return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case Usage::DepthAttachment: case Usage::DepthRead: return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    case Usage::TransferSrc: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Usage::TransferDst: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    case Usage::VertexOrIndex: return 0;
  }
  return 0;
}

void imageBarrier(VkCommandBuffer cmd, const gpu::Image& image, const State& src, const State& dst) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = src.stage;
  b.srcAccessMask = src.access;
  b.dstStageMask = dst.stage;
  b.dstAccessMask = dst.access;
  b.oldLayout = src.layout;
  b.newLayout = dst.layout;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image.handle();
  b.subresourceRange = {image.aspect(), 0, image.info().mipLevels, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, const State& src, const State& dst) {
  gpu::memoryBarrier(cmd, src.stage, src.access, dst.stage, dst.access);
}

// Contents of a transient do not survive, and the memory may have held another resource:
// wait for everything before it, and discard the old layout.
const State kUndefined{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};

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

void PassContext::beginRendering(const std::vector<Attachment>& colors, const std::optional<Attachment>& depth,
                                 std::optional<VkExtent2D> area) {
  std::vector<VkRenderingAttachmentInfo> colorInfos;
  VkExtent3D extent{0, 0, 1};
  for (auto& c : colors) {
    const gpu::Image& img = image(c.name);
    extent = img.extent();
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = img.view();
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
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
    depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
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

Executor::Executor(gpu::Device& device) : device_(device), timestamps_(device, 256) {}

Executor::~Executor() { device_.waitIdle(); }

Executor::Physical& Executor::find(std::string_view name) {
  auto it = physical_.find(name);
  TL_CHECK(it != physical_.end(), "resource `{}` has no physical resource this frame (was it imported?)", name);
  return it->second;
}

void Executor::bindImportedImage(std::string_view name, gpu::Image& image, VkImageLayout currentLayout) {
  auto& p = physical_[std::string(name)];
  p.kind = Physical::Kind::Imported;
  p.image = &image;
  p.buffer = nullptr;
  p.layout = currentLayout;
}

void Executor::bindImportedBuffer(std::string_view name, gpu::Buffer& buffer) {
  auto& p = physical_[std::string(name)];
  p.kind = Physical::Kind::Imported;
  p.buffer = &buffer;
  p.image = nullptr;
}

VkImageLayout Executor::importedLayout(std::string_view name) const {
  auto it = physical_.find(name);
  return it == physical_.end() ? VK_IMAGE_LAYOUT_UNDEFINED : it->second.layout;
}

const gpu::Image* Executor::image(std::string_view name) const {
  auto it = physical_.find(name);
  return it == physical_.end() ? nullptr : it->second.image;
}

VkImageLayout Executor::layout(std::string_view name) const {
  auto it = physical_.find(name);
  return it == physical_.end() ? VK_IMAGE_LAYOUT_UNDEFINED : it->second.layout;
}

void Executor::resetHistory() {
  for (auto& [name, p] : physical_)
    if (p.kind == Physical::Kind::Persistent) p.historyValid = false, p.layout = VK_IMAGE_LAYOUT_UNDEFINED;
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

  // What the inspector, captures and the dump show.
  physicalInfo_.clear();
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
    physicalInfo_.push_back(pi);
  }
}

void Executor::placeBarriers(VkCommandBuffer cmd, const RenderGraph& graph, const CompiledPass& pass) {
  for (const Barrier& b : pass.barriers) {
    const auto& decl = graph.resources()[b.resource];
    Physical& p = find(decl.name);
    State dst = stateFor(b.after, b.afterKind);
    if (p.image) {
      // A transient's first use discards its contents. Persistent and imported images keep
      // theirs: the old layout is the one the executor tracked (previous frame, owner).
      State src = kUndefined;
      if (p.layout != VK_IMAGE_LAYOUT_UNDEFINED && (b.before || p.kind != Physical::Kind::Transient)) {
        src = b.before ? stateFor(*b.before, b.beforeKind)
                       : State{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, p.layout};
        src.layout = p.layout;
      }
      imageBarrier(cmd, *p.image, src, dst);
      p.layout = dst.layout;
    } else {
      State src = b.before ? stateFor(*b.before, b.beforeKind) : kUndefined;
      memoryBarrier(cmd, src, dst);
    }
  }
}

void Executor::copyForReadback(VkCommandBuffer cmd, const std::string& name, Physical& p, Usage usage, PassKind kind) {
  State now = stateFor(usage, kind);
  if (p.image) {
    const gpu::Image& img = *p.image;
    auto fi = gpu::formatInfo(img.format());
    if (fi.bytes == 0) return;
    VkExtent3D e = img.extent();
    VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * e.depth * fi.bytes;
    PendingReadback r{name, img.format(), e,
                      gpu::Buffer(device_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                                  "readback." + name)};
    State copy{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    now.layout = p.layout;
    imageBarrier(cmd, img, now, copy);
    VkBufferImageCopy region{};
    region.imageSubresource = {img.aspect(), 0, 0, 1};
    region.imageExtent = e;
    vkCmdCopyImageToBuffer(cmd, img.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.staging.handle(), 1, &region);
    State back = now;
    back.stage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    back.access = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    imageBarrier(cmd, img, {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}, back);
    pending_.push_back(std::move(r));
  } else if (p.buffer) {
    PendingReadback r{name, VK_FORMAT_UNDEFINED, {uint32_t(p.buffer->size()), 1, 1},
                      gpu::Buffer(device_, p.buffer->size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                                  "readback." + name)};
    memoryBarrier(cmd, now, {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED});
    VkBufferCopy region{0, 0, p.buffer->size()};
    vkCmdCopyBuffer(cmd, p.buffer->handle(), r.staging.handle(), 1, &region);
    memoryBarrier(cmd, {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_IMAGE_LAYOUT_UNDEFINED},
                  {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                   VK_IMAGE_LAYOUT_UNDEFINED});
    pending_.push_back(std::move(r));
  }
}

void Executor::execute(const RenderGraph& graph, const CompiledGraph& compiled) {
  realise(graph, compiled);
  VkCommandBuffer cmd = device_.beginCommands();
  timestamps_.reset(cmd);
  pending_.clear();
  readbacks_.clear();

  for (const CompiledPass& cp : compiled.order) {
    const PassDecl& decl = graph.passes()[cp.pass];
    device_.beginLabel(cmd, decl.name);
    timestamps_.begin(cmd, decl.name);
    placeBarriers(cmd, graph, cp);
    PassContext ctx(device_, *this, decl, cp);
    ctx.cmd = cmd;
    ctx.frameIndex = frame_;
    if (decl.execute) decl.execute(ctx);
    timestamps_.end(cmd);
    device_.endLabel(cmd);
    // A resource has one writer, so its contents are final right after it: read back
    // there, before aliasing can reuse the memory.
    for (const Access& w : cp.writes) {
      const auto& name = graph.resources()[w.resource].name;
      if (readbackAll_ || readbackNames_.count(name)) copyForReadback(cmd, name, find(name), w.usage, decl.kind);
    }
  }
  // Persistent resources no pass wrote this frame (history read but not rewritten, a cache
  // that was not rebuilt) hold their last contents: read those back at the end.
  for (auto& [name, p] : physical_) {
    if (p.kind != Physical::Kind::Persistent || !p.historyValid || !graph.find(name)) continue;
    if (p.image && p.layout == VK_IMAGE_LAYOUT_UNDEFINED) continue;
    if (!readbackAll_ && !readbackNames_.count(name)) continue;
    const std::string& resource = name;  // clang 14 cannot capture a structured binding
    if (std::any_of(pending_.begin(), pending_.end(), [&](const PendingReadback& r) { return r.name == resource; })) continue;
    copyForReadback(cmd, name, p, Usage::Sampled, PassKind::Compute);
  }
  device_.wait(device_.submit(cmd));

  // A persistent resource holds something for the next frame only if a pass of this frame
  // wrote it; one nobody wrote keeps what it had (nothing, after a reset or a resize).
  const auto& decls = graph.resources();
  for (const auto& cp : compiled.order)
    for (const auto& a : cp.writes)
      if (decls[a.resource].persistent) find(decls[a.resource].name).historyValid = true;
  timings_.clear();
  for (auto& s : timestamps_.read()) timings_.push_back({s.name, s.milliseconds});
  for (auto& r : pending_) {
    Readback out{r.name, r.format, r.extent, std::vector<uint8_t>(r.staging.size())};
    std::memcpy(out.bytes.data(), r.staging.mapped(), out.bytes.size());
    readbacks_[r.name] = std::move(out);
  }
  pending_.clear();
  readbackNames_.clear();
  readbackAll_ = false;
  ++frame_;
}

}  // namespace tl::graph
