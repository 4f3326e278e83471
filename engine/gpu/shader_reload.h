// Hot shader reload: GLSL sources edited while the program runs are recompiled with glslang
// into an override folder that loadSpirv() reads first, and every pipeline built from them
// rebuilds itself at its next bind (Pipeline::refresh). A source that fails to compile, or
// a pipeline that fails to build, is reported with its file and line and the last good
// pipeline keeps running.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tl::gpu {

// Bumped by every successful reload; a pipeline built at an older generation rebuilds.
uint64_t shaderGeneration();
// Where freshly compiled SPIR-V is looked up before the build's shader folder ("" = none).
void setShaderOverrideDirectory(const std::filesystem::path& dir);
const std::filesystem::path& shaderOverrideDirectory();
// Pipelines report here when a rebuild fails (the old one stays); the reloader lists them.
void reportPipelineError(const std::string& pipeline, const std::string& message);

struct ShaderReloadResult {
  std::vector<std::string> recompiled;  // shader paths relative to the source folder
  std::vector<std::string> errors;      // glslang's messages: "ERROR: <file>:<line>: ..."
};

class ShaderReloader {
 public:
  // `sources`: the shaders/ folder (default: the source tree's). `output`: where SPIR-V goes.
  // `plugins`: a second source root, the plugins/ folder (default: the source tree's, when
  // `sources` is the default too): a stage there, plugins/<name>/shaders/x.comp, is compiled
  // to the shader path "plugins/<name>/shaders/x.comp" (as the build does, cmake/Shaders.cmake),
  // with `sources` on its include path like every shader.
  explicit ShaderReloader(std::filesystem::path sources = {}, std::filesystem::path output = {},
                          std::filesystem::path plugins = {});
  // Back to the build's shaders: the override folder goes, pipelines rebuild from the build.
  ~ShaderReloader();
  ShaderReloader(const ShaderReloader&) = delete;
  ShaderReloader& operator=(const ShaderReloader&) = delete;

  // Recompiles the shader stages whose file, or any file they include, changed since the
  // last poll (the first poll only records the state). Successful ones take effect at the
  // next bind of their pipelines; failed ones change nothing.
  ShaderReloadResult poll();
  // Errors still standing (a compile error until fixed, pipeline build errors since the
  // last successful reload).
  std::vector<std::string> errors() const;
  const std::filesystem::path& sources() const { return sources_; }
  const std::filesystem::path& plugins() const { return plugins_; }

 private:
  std::filesystem::path sources_, output_, plugins_;
  std::map<std::filesystem::path, std::filesystem::file_time_type> stamps_;
  std::map<std::string, std::string> compileErrors_;  // shader -> message
  bool primed_ = false;
};

}  // namespace tl::gpu
