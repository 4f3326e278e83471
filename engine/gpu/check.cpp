#include "gpu/check.h"

#include <fmt/format.h>

namespace tl::gpu {

const char* resultName(VkResult r) {
  switch (r) {
#define TL_CASE(x) case x: return #x;
    TL_CASE(VK_SUCCESS) TL_CASE(VK_NOT_READY) TL_CASE(VK_TIMEOUT) TL_CASE(VK_INCOMPLETE)
    TL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY) TL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TL_CASE(VK_ERROR_INITIALIZATION_FAILED) TL_CASE(VK_ERROR_DEVICE_LOST)
    TL_CASE(VK_ERROR_MEMORY_MAP_FAILED) TL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    TL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT) TL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    TL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER) TL_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    TL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED) TL_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    TL_CASE(VK_SUBOPTIMAL_KHR) TL_CASE(VK_ERROR_SURFACE_LOST_KHR)
#undef TL_CASE
    default: return "VkResult(?)";
  }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
  throw Error(fmt::format("Vulkan call failed: {} returned {} ({}:{})", call, resultName(result), file, line));
}

}  // namespace tl::gpu
