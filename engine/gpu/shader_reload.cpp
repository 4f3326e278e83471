#include "gpu/shader_reload.h"

#include "gpu/install_paths.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <unistd.h>

namespace tl::gpu {
namespace {

std::atomic<uint64_t> generation{0};
std::filesystem::path overrideDir;
std::mutex pipelineErrorsMutex;
std::map<std::string, std::string> pipelineErrors;  // pipeline -> message

const std::set<std::string> kStages = {".vert", ".frag", ".comp", ".rgen", ".rchit", ".rmiss", ".rahit"};

bool isShaderSource(const std::filesystem::path& p) {
  const std::string e = p.extension().string();
  return kStages.count(e) || e == ".glsl" || e == ".h";
}

// The files a source includes, directly and through its includes (paths under `root`).
void includesOf(const std::filesystem::path& file, const std::filesystem::path& root, std::set<std::filesystem::path>& out) {
  std::ifstream in(file);
  static const std::regex include(R"re(^\s*#\s*include\s+"([^"]+)")re");
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (!std::regex_search(line, m, include)) continue;
    for (const auto& base : {file.parent_path(), root}) {
      std::filesystem::path p = (base / m[1].str()).lexically_normal();
      if (std::filesystem::exists(p)) {
        if (out.insert(p).second) includesOf(p, root, out);
        break;
      }
    }
  }
}

// Runs glslang; empty on success, else its messages.
std::string compile(const std::filesystem::path& source, const std::filesystem::path& root, const std::filesystem::path& spv) {
  std::filesystem::create_directories(spv.parent_path());
  const std::filesystem::path temporary = spv.string() + ".tmp";
  const std::string cmd = fmt::format("'{}' --quiet --target-env vulkan1.3 -g -I'{}' -o '{}' '{}' 2>&1", TWINLIGHT_GLSLANG,
                                      root.string(), temporary.string(), source.string());
  std::string output;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return "cannot run glslang (" TWINLIGHT_GLSLANG ")";
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) output += buf;
  const int status = pclose(pipe);
  if (status != 0) {
    std::filesystem::remove(temporary);
    if (output.empty()) output = fmt::format("glslang failed on {} (status {})", source.string(), status);
    while (!output.empty() && output.back() == '\n') output.pop_back();
    return output;
  }
  std::filesystem::rename(temporary, spv);  // whole or not at all: a reader never sees half a file
  return {};
}

}  // namespace

uint64_t shaderGeneration() { return generation.load(); }
void setShaderOverrideDirectory(const std::filesystem::path& dir) { overrideDir = dir; }
const std::filesystem::path& shaderOverrideDirectory() { return overrideDir; }

void reportPipelineError(const std::string& pipeline, const std::string& message) {
  std::lock_guard<std::mutex> lock(pipelineErrorsMutex);
  pipelineErrors[pipeline] = message;
  spdlog::error("pipeline `{}` kept its last good shaders: {}", pipeline, message);
}

ShaderReloader::ShaderReloader(std::filesystem::path sources, std::filesystem::path output, std::filesystem::path plugins)
    : sources_(sources.empty() ? shaderSourceDirectory() : sources),
      output_(output.empty() ? std::filesystem::temp_directory_path() / fmt::format("twinlight-shaders-{}", getpid())
                             : std::move(output)),
      plugins_(plugins.empty() && sources.empty() ? pluginSourceDirectory() : std::move(plugins)) {
  setShaderOverrideDirectory(output_);
}

ShaderReloader::~ShaderReloader() {
  setShaderOverrideDirectory({});
  std::error_code ec;
  std::filesystem::remove_all(output_, ec);
  ++generation;
}

ShaderReloadResult ShaderReloader::poll() {
  ShaderReloadResult result;
  std::set<std::filesystem::path> changed;
  // Each stage with the shader path it compiles to: relative to shaders/, or for a plugin's,
  // "plugins/" + its path relative to plugins/.
  std::vector<std::pair<std::filesystem::path, std::string>> named;
  auto scan = [&](const std::filesystem::path& root, const std::string& prefix) {
    std::error_code ec;
    if (root.empty()) return;
    for (auto it = std::filesystem::recursive_directory_iterator(root, ec); !ec && it != std::filesystem::recursive_directory_iterator();
         it.increment(ec)) {
      const std::filesystem::path p = it->path().lexically_normal();
      if (!it->is_regular_file() || !isShaderSource(p)) continue;
      const auto stamp = std::filesystem::last_write_time(p, ec);
      auto [entry, added] = stamps_.try_emplace(p, stamp);
      if (!added && entry->second != stamp) changed.insert(p), entry->second = stamp;
      if (kStages.count(p.extension().string()))
        named.emplace_back(p, prefix + std::filesystem::relative(p, root).generic_string());
    }
  };
  scan(sources_, "");
  scan(plugins_, "plugins/");
  if (!primed_) {
    primed_ = true;
    return result;
  }
  if (changed.empty()) return result;

  bool any = false;
  for (const auto& [stage, relative] : named) {
    std::set<std::filesystem::path> deps{stage};
    includesOf(stage, sources_, deps);
    if (std::none_of(deps.begin(), deps.end(), [&](const auto& d) { return changed.count(d); })) continue;
    const std::string error = compile(stage, sources_, output_ / (relative + ".spv"));
    if (error.empty()) {
      compileErrors_.erase(relative);
      result.recompiled.push_back(relative);
      any = true;
    } else {
      compileErrors_[relative] = error;
      result.errors.push_back(error);
      spdlog::error("shader {} did not compile; the last good one keeps running:\n{}", relative, error);
    }
  }
  if (any) {
    std::lock_guard<std::mutex> lock(pipelineErrorsMutex);
    pipelineErrors.clear();
    ++generation;
  }
  return result;
}

std::vector<std::string> ShaderReloader::errors() const {
  std::vector<std::string> out;
  for (auto& [shader, message] : compileErrors_) out.push_back(message);
  std::lock_guard<std::mutex> lock(pipelineErrorsMutex);
  for (auto& [pipeline, message] : pipelineErrors) out.push_back(fmt::format("pipeline {}: {}", pipeline, message));
  return out;
}

}  // namespace tl::gpu
