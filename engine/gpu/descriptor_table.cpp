#include "gpu/descriptor_table.h"

#include "gpu/check.h"

#include <fmt/format.h>

#include <utility>

namespace tl::gpu {

DescriptorTable::DescriptorTable(Device& device, const std::vector<Binding>& bindings, uint32_t variableCount,
                                 std::string_view name)
    : device_(&device) {
  const VkShaderStageFlags all = VK_SHADER_STAGE_ALL;
  std::vector<VkDescriptorSetLayoutBinding> b;
  std::vector<VkDescriptorBindingFlags> flags;
  std::vector<VkDescriptorPoolSize> sizes;
  for (size_t i = 0; i < bindings.size(); ++i) {
    bool variable = i + 1 == bindings.size() && variableCount > 0;
    uint32_t count = variable ? variableCount : bindings[i].count;
    b.push_back({bindings[i].binding, bindings[i].type, count, all, nullptr});
    flags.push_back(variable ? VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT : 0);
    sizes.push_back({bindings[i].type, count});
  }
  VkDescriptorSetLayoutBindingFlagsCreateInfo fi{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO};
  fi.bindingCount = uint32_t(flags.size());
  fi.pBindingFlags = flags.data();
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, &fi};
  lci.bindingCount = uint32_t(b.size());
  lci.pBindings = b.data();
  // The layout is the device's, shared by every table of the same shape (each scene's).
  std::string key = "table";
  for (size_t i = 0; i < b.size(); ++i)
    key += fmt::format(" {}:{}x{}/{}", b[i].binding, int(b[i].descriptorType), b[i].descriptorCount, flags[i]);
  layout_ = device.sharedSetLayout(key, lci);
  device.setName(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, uint64_t(layout_), name);

  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = uint32_t(sizes.size());
  pci.pPoolSizes = sizes.data();
  TL_VK(vkCreateDescriptorPool(device.handle(), &pci, nullptr, &pool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout_;
  TL_VK(vkAllocateDescriptorSets(device.handle(), &ai, &set_));
  device.setName(VK_OBJECT_TYPE_DESCRIPTOR_SET, uint64_t(set_), name);
}

DescriptorTable& DescriptorTable::operator=(DescriptorTable&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pool_ = std::exchange(o.pool_, VK_NULL_HANDLE);
    set_ = std::exchange(o.set_, VK_NULL_HANDLE);
  }
  return *this;
}

void DescriptorTable::reset() {
  if (device_ && layout_) {
    VkDevice d = device_->handle();
    VkDescriptorPool p = pool_;
    device_->destroyLater([d, p] { vkDestroyDescriptorPool(d, p, nullptr); });  // the layout is the device's
  }
  layout_ = VK_NULL_HANDLE;
  pool_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
}

void DescriptorTable::writeBuffer(uint32_t binding, VkDescriptorType type, VkBuffer buffer) {
  VkDescriptorBufferInfo bi{buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  w.pBufferInfo = &bi;
  vkUpdateDescriptorSets(device_->handle(), 1, &w, 0, nullptr);
}

void DescriptorTable::writeImages(uint32_t binding, const std::vector<VkImageView>& views, VkSampler sampler) {
  writeImages(binding, views, std::vector<VkSampler>(views.size(), sampler));
}

void DescriptorTable::writeImages(uint32_t binding, const std::vector<VkImageView>& views, const std::vector<VkSampler>& samplers) {
  if (views.empty()) return;
  TL_CHECK(samplers.size() == views.size(), "{} samplers for {} image views", samplers.size(), views.size());
  std::vector<VkDescriptorImageInfo> infos;
  for (size_t i = 0; i < views.size(); ++i) infos.push_back({samplers[i], views[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = binding;
  w.descriptorCount = uint32_t(infos.size());
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = infos.data();
  vkUpdateDescriptorSets(device_->handle(), 1, &w, 0, nullptr);
}

void DescriptorTable::bind(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout, uint32_t setIndex) const {
  vkCmdBindDescriptorSets(cmd, point, layout, setIndex, 1, &set_, 0, nullptr);
}

}  // namespace tl::gpu
