// Script commands on the scene and its files: open, path, select, warnings and the report,
// reloading after a file changes, animation, the camera, shader sources.
#include "script_commands.h"

#include "editor_app.h"
#include "gpu/install_paths.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace tl::editor {
namespace {

void open(EditorApp& app, ScriptState& s, const std::string& arg) {
  std::filesystem::path p = arg;
  if (p.is_relative() && !std::filesystem::exists(p)) p = gpu::contentDirectory().parent_path() / p;  // "content/x.gltf"
  app.openScene(p);
  s.waitLoaded = true;
}

void waitLoaded(EditorApp&, ScriptState& s, const std::string&) { s.waitLoaded = true; }

void path(EditorApp& app, ScriptState&, const std::string& arg) {
  app.session().setPath(arg);
  app.settings().lightingPath = arg;
}

void select(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& inst = app.session().scene().instances;
  auto it = std::find_if(inst.begin(), inst.end(), [&](auto& i) { return i.name == arg; });
  if (it == inst.end()) throw ScriptFailure(fmt::format("no instance called `{}`", arg));
  app.select(uint32_t(it - inst.begin()));
}

void expectSelected(EditorApp& app, ScriptState&, const std::string& arg) {
  std::string got = app.selected() ? app.session().scene().instances[*app.selected()].name : "none";
  if (got != arg) throw ScriptFailure(fmt::format("expected `{}` to be selected, but `{}` is", arg, got));
  fmt::print("script: `{}` is selected\n", got);
}

void expectSceneWarnings(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& warnings = app.session().scene().warnings;
  if (std::to_string(warnings.size()) != arg)
    throw ScriptFailure(fmt::format("expected {} scene warning(s), but there are {}", arg, warnings.size()));
  if (!warnings.empty() && !app.scenePanelOpen()) throw ScriptFailure("the Scene panel is not open");
  fmt::print("script: {} scene warning(s)\n", warnings.size());
  for (const auto& w : warnings) fmt::print("script: warning: {}\n", w);
}

// A line of the Scene panel's report (what `twinlight info --scene` prints) holds `arg`.
void expectSceneReport(EditorApp& app, ScriptState&, const std::string& arg) {
  if (!app.scenePanelOpen()) throw ScriptFailure("the Scene panel is not open");
  const auto& report = app.sceneReport();
  const auto line =
      std::find_if(report.begin(), report.end(), [&](const std::string& l) { return l.find(arg) != std::string::npos; });
  if (line == report.end()) throw ScriptFailure(fmt::format("no line of the scene report holds `{}`", arg));
  fmt::print("script: scene report: {}\n", *line);
}

void copyFile(EditorApp& app, ScriptState& s, const std::string& arg) {
  std::istringstream files(arg);
  std::string src, dst;
  if (!(files >> src >> dst)) throw ScriptFailure("copy-file needs SRC DST");
  // As an exporter writes: the whole file under another name, then renamed over the old.
  const std::filesystem::path tmp = dst + ".part";
  std::error_code ec;
  std::filesystem::copy_file(src, tmp, std::filesystem::copy_options::overwrite_existing, ec);
  if (!ec) std::filesystem::rename(tmp, dst, ec);
  if (ec) throw ScriptFailure(fmt::format("cannot copy {} to {}: {}", src, dst, ec.message()));
  s.reloadsAtCopy = app.sceneReloads();
  s.cameraAtCopy = app.cameraView().position;
}

void expectReload(EditorApp&, ScriptState& s, const std::string&) {
  s.reloadWaiting = true;
  s.reloadWaitStart = std::chrono::steady_clock::now();
}

void appendLine(EditorApp&, ScriptState&, const std::string& arg) {
  const auto space = arg.find(' ');
  if (space == std::string::npos) throw ScriptFailure("append-line needs FILE TEXT");
  std::ofstream out(arg.substr(0, space), std::ios::app);
  out << "\n" << arg.substr(space + 1) << "\n";
  out.close();
  if (out.fail()) throw ScriptFailure(fmt::format("cannot append to {}", arg.substr(0, space)));
}

void expectShaderError(EditorApp& app, ScriptState& s, const std::string& arg) {
  if (!app.shaderReloader()) throw ScriptFailure("no hot shader reload (shader sources not found)");
  s.waitShaderError = arg;
  s.shaderErrorFrames = 0;
}

// play, pause, or a time in seconds (pauses there).
void animation(EditorApp& app, ScriptState&, const std::string& arg) {
  if (arg == "play" || arg == "pause") {
    app.playing() = arg == "play";
  } else {
    app.playing() = false;
    app.session().setAnimationTime(std::stod(arg));
  }
}

void cameraMove(EditorApp& app, ScriptState& s, const std::string& arg) {
  double x, y, z;
  if (std::sscanf(arg.c_str(), "%lf %lf %lf", &x, &y, &z) != 3) throw ScriptFailure("camera-move needs X Y Z (metres)");
  app.moveCamera({x, y, z});
  if (const session::LiveCompare* live = app.session().liveCompare())
    s.samplesAtMove = live->referenceSamples(), s.restartsAtMove = live->referenceRestarts();
}

constexpr ScriptCommand kCommands[] = {
    {"open", open},
    {"wait-loaded", waitLoaded},
    {"path", path},
    {"select", select},
    {"expect-selected", expectSelected},
    {"expect-scene-warnings", expectSceneWarnings},
    {"expect-scene-report", expectSceneReport},
    {"copy-file", copyFile},
    {"expect-reload", expectReload},
    {"append-line", appendLine},
    {"expect-shader-error", expectShaderError},
    {"animation", animation},
    {"camera-move", cameraMove},
};

}  // namespace

std::span<const ScriptCommand> sceneScriptCommands() { return kCommands; }

}  // namespace tl::editor
