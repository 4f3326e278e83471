// The set-0 descriptor bindings a SPIR-V module declares, read from the module itself: what a
// pass builder checks its declared list against, so a binding the shader has and the pass
// forgot (or declared with another type) is one clear error naming both, not a validation
// message at the first dispatch. Only what push-descriptor sets use is recognised.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tl::gpu {

struct ReflectedBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;  // MAX_ENUM: a kind this reader does not know
  std::string name;                                     // the shader's variable (or its block's) name
};

// Throws gpu::Error on a module that is not SPIR-V.
std::vector<ReflectedBinding> reflectSet0(const std::vector<uint32_t>& spirv);

}  // namespace tl::gpu
