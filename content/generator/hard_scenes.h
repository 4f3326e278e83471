// The hard-case corpus (content/hard/), written by the generator next to the project's scenes.
#pragma once

#include "gltf_writer.h"

#include <filesystem>

namespace tl::content {

void writeHardScenes(const std::filesystem::path& dir);

}  // namespace tl::content
