#pragma once

namespace tl::gpu {

// Marks every shared library loaded so far as never to be unloaded (RTLD_NODELETE).
// Sanitizer builds call it after vkCreateInstance: the Vulkan loader dlcloses the driver and
// the layers at vkDestroyInstance, and LeakSanitizer, which reports at exit, then sees their
// frames as "<unknown module>" -- it can neither name them nor match tests/sanitizer/lsan.supp,
// so every Vulkan process fails on the driver's own allocations. Debian's loader (1.3.239)
// predates VK_LOADER_DISABLE_DYNAMIC_LIBRARY_UNLOADING, which would do the same.
void keepLoadedLibrariesLoaded();

}  // namespace tl::gpu
