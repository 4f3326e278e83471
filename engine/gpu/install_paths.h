// Where the program's data lives, found from the executable's own location so that the
// build tree, an installed tree (`cmake --install`, the .deb) and either one moved elsewhere
// all work without the source tree. An installed tree is laid out as
//   <prefix>/bin/twinlight
//   <prefix>/share/twinlight/shaders/   compiled SPIR-V
//   <prefix>/share/twinlight/content/   the project's scenes
// and the build tree stages its SPIR-V the same way (<build>/share/twinlight/shaders).
#pragma once

#include <filesystem>

namespace tl::gpu {

// The folder of the running executable (/proc/self/exe); empty if it cannot be read.
std::filesystem::path executableDirectory();
// Compiled shaders: $TWINLIGHT_SHADER_DIR, else the nearest share/twinlight/shaders beside
// or above the executable, else the build tree's as configured.
std::filesystem::path shaderDirectory();
// The project's scenes: $TWINLIGHT_ROOT/content, else the nearest share/twinlight/content
// beside or above the executable, else the source tree's content/ as configured.
std::filesystem::path contentDirectory();
// GLSL sources for hot reload: $TWINLIGHT_SHADER_SOURCES, else the source tree's shaders/
// when it still exists; empty when there are none (an installed program without sources).
std::filesystem::path shaderSourceDirectory();
// Plugin sources for hot reload (their shaders/ folders): $TWINLIGHT_PLUGIN_SOURCES, else the
// source tree's plugins/ when it exists; empty otherwise.
std::filesystem::path pluginSourceDirectory();

}  // namespace tl::gpu
