#include "gpu/keep_libraries_loaded.h"

#include <dlfcn.h>
#include <link.h>

namespace tl::gpu {

void keepLoadedLibrariesLoaded() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void*) -> int {
        // The main program has an empty name; every other object is reopened by its path,
        // which only adds a reference (RTLD_NOLOAD) and the no-unload flag.
        if (info->dlpi_name && info->dlpi_name[0] != '\0') {
          void* handle = dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
          if (handle) dlclose(handle);  // the flag stays; the extra reference goes
        }
        return 0;
      },
      nullptr);
}

}  // namespace tl::gpu
