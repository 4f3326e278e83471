// A long-lived descriptor set (not pushed): the scene's texture table, materials and
// instances, bound as set 1 by every pass that shades scene geometry. The last binding
// may be a variable-sized, partially bound array (the texture table).
#pragma once

#include "gpu/pipeline.h"

#include <vector>

namespace tl::gpu {

class DescriptorTable {
 public:
  DescriptorTable() = default;
  // `bindings` with the last one optionally an array of up to `variableCount` elements.
  DescriptorTable(Device& device, const std::vector<Binding>& bindings, uint32_t variableCount, std::string_view name);
  ~DescriptorTable() { reset(); }
  DescriptorTable(DescriptorTable&& o) noexcept { *this = std::move(o); }
  DescriptorTable& operator=(DescriptorTable&& o) noexcept;
  void reset();

  VkDescriptorSetLayout layout() const { return layout_; }
  VkDescriptorSet set() const { return set_; }

  void writeBuffer(uint32_t binding, VkDescriptorType type, VkBuffer buffer);
  void writeImages(uint32_t binding, const std::vector<VkImageView>& views, VkSampler sampler);
  // One sampler per view (samplers[i] goes with views[i]).
  void writeImages(uint32_t binding, const std::vector<VkImageView>& views, const std::vector<VkSampler>& samplers);
  void bind(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout, uint32_t setIndex) const;

 private:
  Device* device_ = nullptr;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace tl::gpu
