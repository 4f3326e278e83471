// A plain descriptor pool for code that allocates its own sets (Dear ImGui's Vulkan backend).
#pragma once

#include "gpu/device.h"

namespace tl::gpu {

class DescriptorPool {
 public:
  DescriptorPool(Device& device, uint32_t maxSets, std::string_view name);
  ~DescriptorPool();
  DescriptorPool(const DescriptorPool&) = delete;
  DescriptorPool& operator=(const DescriptorPool&) = delete;
  VkDescriptorPool handle() const { return pool_; }

 private:
  Device& device_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

}  // namespace tl::gpu
