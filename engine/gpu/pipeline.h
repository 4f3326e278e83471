// Pipelines from SPIR-V: compute, graphics (dynamic rendering) and ray tracing (with its
// shader binding table). Set 0 of every pipeline is a push-descriptor set whose bindings
// come from named constants in shaders/shared/*.h; further sets (e.g. the scene's texture
// table) are passed in as layouts. DescriptorWriter fills set 0 at record time.
#pragma once

#include "gpu/install_paths.h"
#include "gpu/resources.h"

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace tl::gpu {

// Loads <shader dir>/<relative>.spv, e.g. "common/composite.comp" (shaderDirectory(),
// gpu/install_paths.h).
std::vector<uint32_t> loadSpirv(const std::string& relative);

struct Binding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  uint32_t count = 1;
  // May be left unwritten (partially bound): an optional input the shader is told is absent.
  bool optional = false;
  bool operator==(const Binding&) const = default;
};

struct PipelineLayoutDesc {
  std::vector<Binding> bindings;                 // set 0, pushed per dispatch/draw
  std::vector<VkDescriptorSetLayout> extraSets;  // sets 1..N
  uint32_t pushConstantBytes = 0;
};

struct ComputePipelineDesc {
  std::string name;
  std::string shader;  // relative path, e.g. "common/tonemap.comp"
  PipelineLayoutDesc layout;
};

struct GraphicsPipelineDesc {
  std::string name;
  std::string vertexShader;
  std::string fragmentShader;  // empty: depth only
  PipelineLayoutDesc layout;
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  // Vertex buffers and attributes (empty: no vertex input, e.g. a full-screen triangle).
  std::vector<VkVertexInputBindingDescription> vertexBindings;
  std::vector<VkVertexInputAttributeDescription> vertexAttributes;
  VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
  bool depthTest = true;
  bool depthWrite = true;
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z
  bool depthBias = false;
  bool depthClamp = false;
};

struct RayTracingPipelineDesc {
  std::string name;
  std::string raygen;
  std::vector<std::string> misses;
  struct HitGroup {
    std::string closestHit;
    std::string anyHit;
  };
  std::vector<HitGroup> hitGroups;
  PipelineLayoutDesc layout;
  uint32_t maxRecursion = 1;
};

class Pipeline {
 public:
  Pipeline() = default;
  ~Pipeline() { reset(); }
  Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }
  Pipeline& operator=(Pipeline&& o) noexcept;
  void reset();

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bindPoint() const { return bindPoint_; }
  const std::string& name() const { return name_; }
  uint32_t pushConstantBytes() const { return pushConstantBytes_; }
  const std::vector<Binding>& bindings() const { return bindings_; }
  explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }
  // After a shader reload (shader_reload.h): rebuilds from the same description with the
  // new SPIR-V. On failure the error is reported and this pipeline stays as it was.
  bool refresh();

  // Ray tracing only: shader binding table regions.
  VkStridedDeviceAddressRegionKHR raygenRegion{}, missRegion{}, hitRegion{}, callableRegion{};

 private:
  friend Pipeline createComputePipeline(Device&, const ComputePipelineDesc&);
  friend Pipeline createGraphicsPipeline(Device&, const GraphicsPipelineDesc&);
  friend Pipeline createRayTracingPipeline(Device&, const RayTracingPipelineDesc&);
  void createLayout(Device& device, const PipelineLayoutDesc& desc, VkShaderStageFlags stages);

  Device* device_ = nullptr;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout pushSet_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  std::string name_;
  uint32_t pushConstantBytes_ = 0;
  VkShaderStageFlags stages_ = 0;
  std::vector<Binding> bindings_;
  Buffer sbt_;
  std::function<Pipeline()> recipe_;  // rebuilds this pipeline from its description
  uint64_t generation_ = 0;           // shaderGeneration() it was built at
};

Pipeline createComputePipeline(Device& device, const ComputePipelineDesc& desc);

// Compute, ray-tracing and graphics pipelines by description, one per distinct (name, shaders, layout),
// kept for the device's life (Device::pipelines()): what pass builders bind, so a pass holds
// no pipeline. A layout naming another set layout (a new scene table's) is another pipeline.
class PipelineCache {
 public:
  const Pipeline& compute(Device& device, const ComputePipelineDesc& desc);
  const Pipeline& rayTracing(Device& device, const RayTracingPipelineDesc& desc);
  const Pipeline& graphics(Device& device, const GraphicsPipelineDesc& desc);
  bool contains(const ComputePipelineDesc& desc) const { return pipelines_.count(key(desc)) != 0; }
  bool contains(const GraphicsPipelineDesc& desc) const { return pipelines_.count(key(desc)) != 0; }
  bool contains(const RayTracingPipelineDesc& desc) const { return pipelines_.count(key(desc)) != 0; }
  size_t size() const { return pipelines_.size(); }

 private:
  static std::string key(const ComputePipelineDesc& desc);
  static std::string key(const RayTracingPipelineDesc& desc);
  static std::string key(const GraphicsPipelineDesc& desc);
  std::map<std::string, Pipeline> pipelines_;
};
Pipeline createGraphicsPipeline(Device& device, const GraphicsPipelineDesc& desc);
Pipeline createRayTracingPipeline(Device& device, const RayTracingPipelineDesc& desc);

// Collects set-0 descriptors for one dispatch/draw and pushes them. Binding numbers come
// from shared-header constants; a binding the pipeline does not declare is an error.
class DescriptorWriter {
 public:
  DescriptorWriter& storageImage(uint32_t binding, VkImageView view);
  DescriptorWriter& sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  DescriptorWriter& storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                                  VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                                  VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& accelerationStructure(uint32_t binding, VkAccelerationStructureKHR as);
  void push(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline);

 private:
  struct Entry {
    uint32_t binding;
    VkDescriptorType type;
    VkDescriptorImageInfo image{};
    VkDescriptorBufferInfo buffer{};
    VkAccelerationStructureKHR as = VK_NULL_HANDLE;
  };
  std::vector<Entry> entries_;
};

}  // namespace tl::gpu
