// Error policy for the Vulkan layer. A failed Vulkan call throws gpu::Error with the call
// and the result spelled out; checks never compile away in release builds. Callers above
// engine/gpu catch it where the failure is recoverable (e.g. "no ray tracing") and show it.
#pragma once

#include <vulkan/vulkan_core.h>

#include <stdexcept>
#include <string>

namespace tl::gpu {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* resultName(VkResult result);
[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

}  // namespace tl::gpu

#define TL_VK(call)                                                               \
  do {                                                                            \
    VkResult tl_vk_result_ = (call);                                              \
    if (tl_vk_result_ != VK_SUCCESS)                                              \
      ::tl::gpu::throwVkError(tl_vk_result_, #call, __FILE__, __LINE__);          \
  } while (0)

#define TL_CHECK(cond, ...)                                                       \
  do {                                                                            \
    if (!(cond)) throw ::tl::gpu::Error(fmt::format(__VA_ARGS__));                \
  } while (0)
