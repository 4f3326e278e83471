#include "gpu/pipeline.h"

#include "gpu/shader_reload.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <utility>

namespace tl::gpu {

std::vector<uint32_t> loadSpirv(const std::string& relative) {
  auto path = shaderDirectory() / (relative + ".spv");
  // A hot-reloaded shader (shader_reload.h) wins over the build's.
  if (!shaderOverrideDirectory().empty() && std::filesystem::exists(shaderOverrideDirectory() / (relative + ".spv")))
    path = shaderOverrideDirectory() / (relative + ".spv");
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) throw Error(fmt::format("shader {} not found (was the project built? expected {})", relative, path.string()));
  auto size = f.tellg();
  if (size <= 0 || size % 4 != 0) throw Error(fmt::format("shader {} is not SPIR-V ({} bytes)", path.string(), int64_t(size)));
  std::vector<uint32_t> words(size_t(size) / 4);
  f.seekg(0);
  f.read(reinterpret_cast<char*>(words.data()), size);
  if (words[0] != 0x07230203u) throw Error(fmt::format("shader {} is not SPIR-V (bad magic)", path.string()));
  return words;
}

namespace {

VkShaderModule createModule(Device& device, const std::string& relative) {
  auto words = loadSpirv(relative);
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = words.size() * 4;
  ci.pCode = words.data();
  VkShaderModule m;
  TL_VK(vkCreateShaderModule(device.handle(), &ci, nullptr, &m));
  device.setName(VK_OBJECT_TYPE_SHADER_MODULE, uint64_t(m), relative);
  return m;
}

VkPipelineShaderStageCreateInfo stageInfo(VkShaderStageFlagBits stage, VkShaderModule m) {
  VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  s.stage = stage;
  s.module = m;
  s.pName = "main";
  return s;
}

struct Modules {
  Device& device;
  std::vector<VkShaderModule> list;
  VkShaderModule add(const std::string& rel) { return list.emplace_back(createModule(device, rel)); }
  ~Modules() {
    for (auto m : list) vkDestroyShaderModule(device.handle(), m, nullptr);
  }
};

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

}  // namespace

void Pipeline::createLayout(Device& device, const PipelineLayoutDesc& desc, VkShaderStageFlags stages) {
  device_ = &device;
  stages_ = stages;
  bindings_ = desc.bindings;
  pushConstantBytes_ = desc.pushConstantBytes;
  std::vector<VkDescriptorSetLayoutBinding> b;
  std::vector<VkDescriptorBindingFlags> flags;
  bool anyOptional = false;
  for (auto& x : desc.bindings) {
    b.push_back({x.binding, x.type, x.count, stages, nullptr});
    flags.push_back(x.optional ? VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT : 0);
    anyOptional |= x.optional;
  }
  VkDescriptorSetLayoutBindingFlagsCreateInfo fci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO};
  fci.bindingCount = uint32_t(flags.size());
  fci.pBindingFlags = flags.data();
  VkDescriptorSetLayoutCreateInfo sci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  if (anyOptional) sci.pNext = &fci;
  sci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  sci.bindingCount = uint32_t(b.size());
  sci.pBindings = b.data();
  TL_VK(vkCreateDescriptorSetLayout(device.handle(), &sci, nullptr, &pushSet_));
  std::vector<VkDescriptorSetLayout> sets{pushSet_};
  sets.insert(sets.end(), desc.extraSets.begin(), desc.extraSets.end());
  VkPushConstantRange pc{stages, 0, desc.pushConstantBytes};
  VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  lci.setLayoutCount = uint32_t(sets.size());
  lci.pSetLayouts = sets.data();
  lci.pushConstantRangeCount = desc.pushConstantBytes ? 1 : 0;
  lci.pPushConstantRanges = &pc;
  TL_VK(vkCreatePipelineLayout(device.handle(), &lci, nullptr, &layout_));
  device.setName(VK_OBJECT_TYPE_PIPELINE_LAYOUT, uint64_t(layout_), name_);
}

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pushSet_ = std::exchange(o.pushSet_, VK_NULL_HANDLE);
    bindPoint_ = o.bindPoint_;
    name_ = std::move(o.name_);
    pushConstantBytes_ = o.pushConstantBytes_;
    stages_ = o.stages_;
    bindings_ = std::move(o.bindings_);
    sbt_ = std::move(o.sbt_);
    recipe_ = std::move(o.recipe_);
    generation_ = o.generation_;
    raygenRegion = o.raygenRegion, missRegion = o.missRegion, hitRegion = o.hitRegion, callableRegion = o.callableRegion;
  }
  return *this;
}

void Pipeline::reset() {
  if (device_ && (pipeline_ || layout_ || pushSet_)) {
    VkDevice d = device_->handle();
    VkPipeline p = pipeline_;
    VkPipelineLayout l = layout_;
    VkDescriptorSetLayout s = pushSet_;
    device_->destroyLater([d, p, l, s] {
      vkDestroyPipeline(d, p, nullptr);
      vkDestroyPipelineLayout(d, l, nullptr);
      vkDestroyDescriptorSetLayout(d, s, nullptr);
    });
  }
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  pushSet_ = VK_NULL_HANDLE;
  sbt_.reset();
}

bool Pipeline::refresh() {
  if (!recipe_ || generation_ == shaderGeneration()) return false;
  generation_ = shaderGeneration();  // one try per reload, not one per bind
  try {
    Pipeline fresh = recipe_();
    *this = std::move(fresh);  // the old objects are destroyed once the GPU is past them
    return true;
  } catch (const std::exception& e) {
    reportPipelineError(name_, e.what());
    return false;
  }
}

Pipeline createComputePipeline(Device& device, const ComputePipelineDesc& desc) {
  Pipeline p;
  p.recipe_ = [&device, desc] { return createComputePipeline(device, desc); };
  p.generation_ = shaderGeneration();
  p.name_ = desc.name;
  p.bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  p.createLayout(device, desc.layout, VK_SHADER_STAGE_COMPUTE_BIT);
  Modules modules{device};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = stageInfo(VK_SHADER_STAGE_COMPUTE_BIT, modules.add(desc.shader));
  ci.layout = p.layout_;
  TL_VK(vkCreateComputePipelines(device.handle(), VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline_));
  device.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline_), desc.name);
  return p;
}

Pipeline createGraphicsPipeline(Device& device, const GraphicsPipelineDesc& desc) {
  Pipeline p;
  p.recipe_ = [&device, desc] { return createGraphicsPipeline(device, desc); };
  p.generation_ = shaderGeneration();
  p.name_ = desc.name;
  p.bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
  p.createLayout(device, desc.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  Modules modules{device};
  std::vector<VkPipelineShaderStageCreateInfo> stages{stageInfo(VK_SHADER_STAGE_VERTEX_BIT, modules.add(desc.vertexShader))};
  if (!desc.fragmentShader.empty())
    stages.push_back(stageInfo(VK_SHADER_STAGE_FRAGMENT_BIT, modules.add(desc.fragmentShader)));

  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = uint32_t(desc.vertexBindings.size());
  vi.pVertexBindingDescriptions = desc.vertexBindings.data();
  vi.vertexAttributeDescriptionCount = uint32_t(desc.vertexAttributes.size());
  vi.pVertexAttributeDescriptions = desc.vertexAttributes.data();
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = desc.cullMode;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.depthBiasEnable = desc.depthBias;
  rs.depthClampEnable = desc.depthClamp;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.depthTest;
  ds.depthWriteEnable = desc.depthWrite;
  ds.depthCompareOp = desc.depthCompare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
  for (auto& b : blends) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blends.size());
  cb.pAttachments = blends.data();
  std::vector<VkDynamicState> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (desc.depthBias) dyn.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = uint32_t(dyn.size());
  dy.pDynamicStates = dyn.data();
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = p.layout_;
  TL_VK(vkCreateGraphicsPipelines(device.handle(), VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline_));
  device.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline_), desc.name);
  return p;
}

Pipeline createRayTracingPipeline(Device& device, const RayTracingPipelineDesc& desc) {
  const auto& rt = device.rayTracing();
  TL_CHECK(rt.pipeline, "ray-tracing pipeline `{}` needs ray tracing: {}", desc.name, rt.unavailableReason);
  Pipeline p;
  p.recipe_ = [&device, desc] { return createRayTracingPipeline(device, desc); };
  p.generation_ = shaderGeneration();
  p.name_ = desc.name;
  p.bindPoint_ = VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR;
  p.createLayout(device, desc.layout,
                 VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR |
                     VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR);
  Modules modules{device};
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups;
  auto general = [&](VkShaderStageFlagBits stage, const std::string& rel) {
    stages.push_back(stageInfo(stage, modules.add(rel)));
    VkRayTracingShaderGroupCreateInfoKHR g{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
    g.generalShader = uint32_t(stages.size() - 1);
    g.closestHitShader = g.anyHitShader = g.intersectionShader = VK_SHADER_UNUSED_KHR;
    groups.push_back(g);
  };
  general(VK_SHADER_STAGE_RAYGEN_BIT_KHR, desc.raygen);
  for (auto& m : desc.misses) general(VK_SHADER_STAGE_MISS_BIT_KHR, m);
  for (auto& h : desc.hitGroups) {
    VkRayTracingShaderGroupCreateInfoKHR g{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    g.generalShader = g.closestHitShader = g.anyHitShader = g.intersectionShader = VK_SHADER_UNUSED_KHR;
    if (!h.closestHit.empty()) {
      stages.push_back(stageInfo(VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, modules.add(h.closestHit)));
      g.closestHitShader = uint32_t(stages.size() - 1);
    }
    if (!h.anyHit.empty()) {
      stages.push_back(stageInfo(VK_SHADER_STAGE_ANY_HIT_BIT_KHR, modules.add(h.anyHit)));
      g.anyHitShader = uint32_t(stages.size() - 1);
    }
    groups.push_back(g);
  }
  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.groupCount = uint32_t(groups.size());
  ci.pGroups = groups.data();
  ci.maxPipelineRayRecursionDepth = desc.maxRecursion;
  ci.layout = p.layout_;
  TL_VK(device.ext().createRayTracingPipelines(device.handle(), VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &ci, nullptr,
                                               &p.pipeline_));
  device.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline_), desc.name);

  // Shader binding table: raygen | misses | hit groups, each region aligned to the base.
  const auto& props = rt.pipelineProperties;
  VkDeviceSize handleSize = props.shaderGroupHandleSize;
  VkDeviceSize stride = alignUp(handleSize, props.shaderGroupHandleAlignment);
  VkDeviceSize base = props.shaderGroupBaseAlignment;
  std::vector<uint8_t> handles(groups.size() * handleSize);
  TL_VK(device.ext().getRayTracingShaderGroupHandles(device.handle(), p.pipeline_, 0, uint32_t(groups.size()),
                                                     handles.size(), handles.data()));
  VkDeviceSize raygenSize = alignUp(stride, base);
  VkDeviceSize missSize = alignUp(stride * desc.misses.size(), base);
  VkDeviceSize hitSize = alignUp(stride * desc.hitGroups.size(), base);
  std::vector<uint8_t> table(raygenSize + missSize + hitSize + base, 0);
  auto copyGroup = [&](size_t group, VkDeviceSize offset) {
    std::memcpy(table.data() + offset, handles.data() + group * handleSize, handleSize);
  };
  copyGroup(0, 0);
  for (size_t i = 0; i < desc.misses.size(); ++i) copyGroup(1 + i, raygenSize + i * stride);
  for (size_t i = 0; i < desc.hitGroups.size(); ++i) copyGroup(1 + desc.misses.size() + i, raygenSize + missSize + i * stride);
  p.sbt_ = Buffer(device, table.size(), VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR, MemoryUsage::Upload, desc.name + ".sbt");
  // The table's start must itself be base-aligned.
  VkDeviceAddress start = alignUp(p.sbt_.address(), base);
  VkDeviceSize shift = start - p.sbt_.address();
  p.sbt_.write(table.data(), table.size() - shift, shift);
  p.raygenRegion = {start, stride, stride};
  p.missRegion = {start + raygenSize, stride, stride * desc.misses.size()};
  p.hitRegion = {start + raygenSize + missSize, stride, stride * desc.hitGroups.size()};
  return p;
}

// ---- DescriptorWriter ------------------------------------------------------------------

namespace {
std::string layoutKey(const PipelineLayoutDesc& layout) {
  std::string key = fmt::format("|{}", layout.pushConstantBytes);
  for (const Binding& b : layout.bindings) key += fmt::format("|{}:{}:{}:{}", b.binding, int(b.type), b.count, b.optional);
  for (VkDescriptorSetLayout s : layout.extraSets) key += fmt::format("|set{}", uint64_t(s));
  return key;
}
}  // namespace

std::string PipelineCache::key(const ComputePipelineDesc& desc) {
  return fmt::format("compute|{}|{}", desc.name, desc.shader) + layoutKey(desc.layout);
}

std::string PipelineCache::key(const RayTracingPipelineDesc& desc) {
  std::string key = fmt::format("rt|{}|{}|{}", desc.name, desc.raygen, desc.maxRecursion);
  for (const std::string& m : desc.misses) key += "|miss:" + m;
  for (const auto& h : desc.hitGroups) key += fmt::format("|hit:{}+{}", h.closestHit, h.anyHit);
  return key + layoutKey(desc.layout);
}

std::string PipelineCache::key(const GraphicsPipelineDesc& desc) {
  std::string key = fmt::format("graphics|{}|{}|{}|{}|{}|{}|{}{}{}{}", desc.name, desc.vertexShader, desc.fragmentShader,
                                int(desc.depthFormat), desc.cullMode, int(desc.depthCompare), desc.depthTest,
                                desc.depthWrite, desc.depthBias, desc.depthClamp);
  for (VkFormat f : desc.colorFormats) key += fmt::format("|color:{}", int(f));
  for (const auto& b : desc.vertexBindings) key += fmt::format("|vb:{}:{}:{}", b.binding, b.stride, int(b.inputRate));
  for (const auto& a : desc.vertexAttributes)
    key += fmt::format("|va:{}:{}:{}:{}", a.location, a.binding, int(a.format), a.offset);
  return key + layoutKey(desc.layout);
}

const Pipeline& PipelineCache::graphics(Device& device, const GraphicsPipelineDesc& desc) {
  const std::string k = key(desc);
  auto it = pipelines_.find(k);
  if (it == pipelines_.end()) it = pipelines_.emplace(k, createGraphicsPipeline(device, desc)).first;
  return it->second;
}

const Pipeline& PipelineCache::compute(Device& device, const ComputePipelineDesc& desc) {
  const std::string k = key(desc);
  auto it = pipelines_.find(k);
  if (it == pipelines_.end()) it = pipelines_.emplace(k, createComputePipeline(device, desc)).first;
  return it->second;
}

const Pipeline& PipelineCache::rayTracing(Device& device, const RayTracingPipelineDesc& desc) {
  const std::string k = key(desc);
  auto it = pipelines_.find(k);
  if (it == pipelines_.end()) it = pipelines_.emplace(k, createRayTracingPipeline(device, desc)).first;
  return it->second;
}

DescriptorWriter& DescriptorWriter::storageImage(uint32_t binding, VkImageView view) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  e.image = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  entries_.push_back(e);
  return *this;
}

DescriptorWriter& DescriptorWriter::sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                                 VkImageLayout layout) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  e.image = {sampler, view, layout};
  entries_.push_back(e);
  return *this;
}

DescriptorWriter& DescriptorWriter::storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset,
                                                  VkDeviceSize range) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  e.buffer = {buffer, offset, range};
  entries_.push_back(e);
  return *this;
}

DescriptorWriter& DescriptorWriter::uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset,
                                                  VkDeviceSize range) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};
  e.buffer = {buffer, offset, range};
  entries_.push_back(e);
  return *this;
}

DescriptorWriter& DescriptorWriter::accelerationStructure(uint32_t binding, VkAccelerationStructureKHR as) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR};
  e.as = as;
  entries_.push_back(e);
  return *this;
}

void DescriptorWriter::push(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline) {
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkWriteDescriptorSetAccelerationStructureKHR> asWrites;
  asWrites.reserve(entries_.size());
  for (auto& e : entries_) {
    bool declared = false;
    for (auto& b : pipeline.bindings()) declared |= (b.binding == e.binding && b.type == e.type);
    TL_CHECK(declared, "pipeline `{}` has no binding {} of the type being written", pipeline.name(), e.binding);
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = e.binding;
    w.descriptorCount = 1;
    w.descriptorType = e.type;
    if (e.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || e.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
      w.pBufferInfo = &e.buffer;
    } else if (e.type == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR) {
      VkWriteDescriptorSetAccelerationStructureKHR a{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
      a.accelerationStructureCount = 1;
      a.pAccelerationStructures = &e.as;
      asWrites.push_back(a);
      w.pNext = &asWrites.back();
    } else {
      w.pImageInfo = &e.image;
    }
    writes.push_back(w);
  }
  // A pipeline whose set 0 is empty (only push constants and further sets) pushes nothing.
  if (!writes.empty())
    device.ext().cmdPushDescriptorSet(cmd, pipeline.bindPoint(), pipeline.layout(), 0, uint32_t(writes.size()),
                                      writes.data());
  entries_.clear();
}

}  // namespace tl::gpu
