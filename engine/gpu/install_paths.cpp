#include "gpu/install_paths.h"

#include <cstdlib>
#include <system_error>

namespace tl::gpu {
namespace {

std::filesystem::path fromEnvironment(const char* name) {
  const char* value = std::getenv(name);
  return value && *value ? std::filesystem::path(value) : std::filesystem::path();
}

// share/twinlight/<what> in the executable's folder or up to two folders above it: bin/ of an
// install, editor/ or tests/gpu/ of the build tree.
std::filesystem::path installed(const char* what) {
  std::filesystem::path dir = executableDirectory();
  std::error_code ec;
  for (int up = 0; up < 3 && !dir.empty(); ++up, dir = dir.parent_path()) {
    const std::filesystem::path candidate = dir / "share" / "twinlight" / what;
    if (std::filesystem::is_directory(candidate, ec)) return candidate;
    if (dir == dir.root_path()) break;
  }
  return {};
}

}  // namespace

std::filesystem::path executableDirectory() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

std::filesystem::path shaderDirectory() {
  if (auto env = fromEnvironment("TWINLIGHT_SHADER_DIR"); !env.empty()) return env;
  if (auto found = installed("shaders"); !found.empty()) return found;
  return TWINLIGHT_SHADER_DIR;
}

std::filesystem::path contentDirectory() {
  if (auto env = fromEnvironment("TWINLIGHT_ROOT"); !env.empty()) return env / "content";
  if (auto found = installed("content"); !found.empty()) return found;
  return std::filesystem::path(TWINLIGHT_SOURCE_ROOT) / "content";
}

std::filesystem::path shaderSourceDirectory() {
  if (auto env = fromEnvironment("TWINLIGHT_SHADER_SOURCES"); !env.empty()) return env;
  const std::filesystem::path source = std::filesystem::path(TWINLIGHT_SOURCE_ROOT) / "shaders";
  std::error_code ec;
  return std::filesystem::is_directory(source, ec) ? source : std::filesystem::path();
}

std::filesystem::path pluginSourceDirectory() {
  if (auto env = fromEnvironment("TWINLIGHT_PLUGIN_SOURCES"); !env.empty()) return env;
  const std::filesystem::path source = std::filesystem::path(TWINLIGHT_SOURCE_ROOT) / "plugins";
  std::error_code ec;
  return std::filesystem::is_directory(source, ec) ? source : std::filesystem::path();
}

}  // namespace tl::gpu
