// What the reference path tracer is made of, for those who must know when it changed: the
// compare command's on-disk reference cache keys its images by a hash of these shaders' SPIR-V.
#pragma once

#include <string>
#include <vector>

namespace tl::lighting {

// The shaders (relative to the shader folder, as gpu::loadSpirv takes them) of every
// pipeline the reference path builds.
std::vector<std::string> referenceShaders();

}  // namespace tl::lighting
