// A short end-to-end check that ray tracing really works on this device: builds a
// one-triangle BLAS and TLAS, traces a 4x4 grid through a ray-tracing pipeline and checks
// every hit distance and miss. `twinlight info` and the GPU tests run it.
#pragma once

#include "gpu/device.h"

#include <optional>
#include <string>

namespace tl::gpu {

// Nothing when every ray returned what it must; otherwise what went wrong.
std::optional<std::string> rayTracingSelfTest(Device& device);

}  // namespace tl::gpu
