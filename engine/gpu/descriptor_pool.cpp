#include "gpu/descriptor_pool.h"

namespace tl::gpu {

DescriptorPool::DescriptorPool(Device& device, uint32_t maxSets, std::string_view name) : device_(device) {
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, maxSets},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, maxSets},
                                  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, maxSets},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, maxSets}};
  VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  ci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  ci.maxSets = maxSets;
  ci.poolSizeCount = 4;
  ci.pPoolSizes = sizes;
  TL_VK(vkCreateDescriptorPool(device.handle(), &ci, nullptr, &pool_));
  device.setName(VK_OBJECT_TYPE_DESCRIPTOR_POOL, uint64_t(pool_), name);
}

DescriptorPool::~DescriptorPool() {
  VkDevice d = device_.handle();
  VkDescriptorPool p = pool_;
  device_.destroyLater([d, p] { vkDestroyDescriptorPool(d, p, nullptr); });
}

}  // namespace tl::gpu
