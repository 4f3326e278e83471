// `twinlight info`: the Vulkan device, its ray-tracing support (with a self-test), the data
// folders and the lighting paths; `info --scene FILE`: what a glTF file holds and what of it
// Twinlight ignores, without a device.
#include "cli_command.h"

#include "cli_args.h"
#include "gpu/install_paths.h"
#include "gpu/self_test.h"
#include "session/session.h"

#include <fmt/format.h>

namespace tl::editor {
namespace {

// What the file holds and what of it Twinlight ignores, one line each (scene::sceneReport).
// Warnings the importer gave are the ignored lines.
int runSceneInfo(const std::string& file) {
  const scene::Scene scene = scene::loadGltf(file);
  fmt::print("scene: {}\n", file);
  for (const auto& line : scene::sceneReport(scene)) fmt::print("{}\n", line);
  for (const auto& w : scene.warnings)
    if (w.find("could not be loaded") != std::string::npos) fmt::print("warning: {}\n", w);
  return 0;
}

int runInfo() {
  session::Session session;
  auto& d = session.device();
  fmt::print("device: {}\ndriver: {}\nvulkan: {}.{}.{}\n", d.name(), d.driver(), VK_API_VERSION_MAJOR(d.apiVersion()),
             VK_API_VERSION_MINOR(d.apiVersion()), VK_API_VERSION_PATCH(d.apiVersion()));
  if (d.rayTracing().pipeline) {
    auto failure = gpu::rayTracingSelfTest(d);
    fmt::print("ray tracing: {}, self-test {}\n", d.rayTracing().query ? "pipeline + query" : "pipeline",
               failure ? "FAILED: " + *failure : std::string("passed"));
  } else {
    fmt::print("ray tracing: unavailable: {}\n", d.rayTracing().unavailableReason);
  }
  fmt::print("shaders: {}\ncontent: {}\n", gpu::shaderDirectory().string(), gpu::contentDirectory().string());
  fmt::print("lighting paths:\n");
  for (auto& p : session.paths()) {
    std::string caps;
    auto add = [&](bool on, const char* what) {
      if (on) caps += fmt::format("{}{}", caps.empty() ? "" : ", ", what);
    };
    add(p.plugin, "plugin");
    add(p.capabilities.isReference, "reference");
    add(p.capabilities.needsRayTracing, "needs ray tracing");
    add(p.capabilities.accumulates, "accumulates");
    add(!p.capabilities.rasterizes, "traces primary rays");
    add(p.capabilities.halfResolution, "half resolution");
    fmt::print("  {:10} {}{}{}\n", p.name, p.description, caps.empty() ? "" : " (" + caps + ")",
               p.available ? "" : "  [unavailable: " + p.unavailableReason + "]");
  }
  return exitStatus(session);
}

class InfoCommand : public CliCommand {
 public:
  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("info", "print the Vulkan device, its ray-tracing support and the lighting paths");
    cmd->add_option("--scene", scene_, "instead: list what a glTF file holds and every feature of it Twinlight ignores, one line each");
    return cmd;
  }
  int run() override { return scene_.empty() ? runInfo() : runSceneInfo(scene_); }

 private:
  std::string scene_;
};

}  // namespace

std::unique_ptr<CliCommand> makeInfoCommand() { return std::make_unique<InfoCommand>(); }

}  // namespace tl::editor
