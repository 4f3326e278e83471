// `twinlight`: one binary. Without a subcommand it shows the default (or given) scene;
// the headless subcommands (editor/commands/, one file each) work on machines without a
// display. Errors are one line on stderr (`twinlight: error: ...`) and a non-zero exit: 2 when
// the command line does not parse, 3 for a regression gate (compare --fail-above) that failed,
// 1 for everything else (bad values, files, failures at run time, and Vulkan validation errors
// when the layers are on).
#include "cli_output.h"
#include "commands/cli_command.h"
#include "commands/render_options.h"
#include "editor_app.h"
#include "session/shard.h"
#include "version/version.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

namespace {

using namespace tl::editor;

bool hasDisplay() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

// No subcommand: the editor on the default (or given) scene. It needs a display (or a
// script); without one the scene is rendered headless into out/.
struct EditorArgs {
  std::string scene, script, materials = "authored", lighting;
  bool headless = false;

  void add(CLI::App& app) {
    app.add_option("scene", scene, "glTF scene to open (default: content/atrium.gltf)");
    const tl::lighting::SettingInfo* setting = tl::lighting::findSetting("materials");
    app.add_option("--materials", materials, std::string(setting->help))->capture_default_str();
    app.add_option("--script", script, "run editor actions from FILE (see editor/script.h), then quit");
    app.add_option("--lighting", lighting,
                   "lighting file (SCENE.lighting.json) for the scene, in place of the one File > Save lighting left beside it");
    app.add_flag("--headless", headless, "render the scene to out/ instead of opening the editor");
  }

  bool window() const { return !headless && (hasDisplay() || !script.empty()); }

  int run() const {
    const auto mode = tl::lighting::parseMaterialMode(materials);
    if (!mode) throw tl::session::SessionError(fmt::format("--materials must be authored, diffuse or clay, not `{}`", materials));
    if (window()) {
      std::optional<std::filesystem::path> sceneFile, scriptFile, lightingFile;
      if (!scene.empty()) sceneFile = scene;
      if (!script.empty()) scriptFile = script;
      if (!lighting.empty()) lightingFile = lighting;
      EditorApp editor(sceneFile, scriptFile, *mode, lightingFile);
      return editor.run();
    }
    RenderOptions o;
    o.scene = scene;
    giveSettingAlias(o.aliases, "materials", materials);
    o.light.lighting = lighting;
    std::filesystem::path stem = scene.empty() ? defaultScene().stem() : std::filesystem::path(scene).stem();
    o.outputs = {(std::filesystem::path("out") / (stem.string() + ".png")).string(),
                 (std::filesystem::path("out") / (stem.string() + ".exr")).string()};
    fmt::print("no display found (DISPLAY/WAYLAND_DISPLAY unset); rendering {} headless\n", stem.string());
    return runRender(o);
  }
};

}  // namespace

int main(int argc, char** argv) {
  configureLogging(Verbosity::Normal, true);
  CLI::App app{"Twinlight: a lighting lab comparing ray-traced and legacy real-time lighting against a path tracer"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", "twinlight " + tl::versionString());
  // -q / -v before or after the subcommand: each takes them (not a fallthrough, which would
  // also hand a subcommand's stray positional argument to the editor's scene).
  bool quiet = false, verbose = false;
  auto addVerbosityFlags = [&](CLI::App& cmd) {
    auto* quietFlag = cmd.add_flag("-q,--quiet", quiet, "errors only: no warnings, no progress (results still on stdout)");
    cmd.add_flag("-v,--verbose", verbose, "info and debug messages on stderr too")->excludes(quietFlag);
  };
  addVerbosityFlags(app);
  EditorArgs editorArgs;
  editorArgs.add(app);

  const auto commands = cliCommands();
  std::vector<std::pair<CLI::App*, CliCommand*>> subcommands;
  for (const auto& command : commands) subcommands.push_back({command->add(app), command.get()});
  for (auto& [cmd, command] : subcommands) addVerbosityFlags(*cmd);
  // Set after the subcommands are added, which would inherit it: `twinlight --help` alone.
  app.footer(helpFooter());
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    fmt::print(stderr, "twinlight: error: {} (see --help)\n", e.what());
    return 2;
  }
  CliCommand* given = nullptr;
  for (auto& [cmd, command] : subcommands)
    if (*cmd) given = command;
  // Timestamps only in the interactive editor's log; a subcommand or a headless render is a
  // command in a pipeline.
  const bool editorWindow = !given && editorArgs.window();
  configureLogging(quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal, !editorWindow);
  if (quiet && verbose) {
    fmt::print(stderr, "twinlight: error: -q and -v contradict each other (see --help)\n");
    return 2;
  }

  try {
    return given ? given->run() : editorArgs.run();
  } catch (const UsageError& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 2;
  } catch (const tl::session::ShardError& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 1;
  }
}
