// Writing images from read-back buffers: EXR (linear half float) and PNG (8-bit display).
// Files are written to a temporary name beside the target and renamed, so a crash or a
// kill never leaves a half-written image under the real name.
#pragma once

#include "graph/executor.h"

#include <filesystem>

namespace tl::session {

enum class ImageEncoding { LinearHalf, Display8 };

void writeImageAtomically(const std::filesystem::path& file, const graph::Readback& image, ImageEncoding encoding);

}  // namespace tl::session
