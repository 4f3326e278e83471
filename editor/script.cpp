#include "script.h"

#include "editor_app.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace tl::editor {

Script::Script(const std::filesystem::path& file) : file_(file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the script", file.string()));
  std::string line;
  while (std::getline(in, line)) lines_.push_back(line);
}

void Script::fail(EditorApp& app, const std::string& why) {
  failure_ = fmt::format("{}:{}: {}", file_.string(), next_, why);
  app.requestQuit();
}

const ScriptCommand* findScriptCommand(std::string_view name) {
  for (auto group : {sceneScriptCommands, inputScriptCommands, viewerScriptCommands, albedoScriptCommands,
                     compareScriptCommands, settingsScriptCommands, frameScriptCommands, lightScriptCommands,
                     workScriptCommands})
    for (const ScriptCommand& c : group())
      if (c.name == name) return &c;
  return nullptr;
}

// One action per frame, as a person would: once no wait holds it, the next line runs.
void Script::step(EditorApp& app) {
  if (failed()) return;
  if (app.input().pending()) return;  // injected input reaches the interface first
  try {
    if (scriptWaiting(app, state_)) return;
  } catch (const std::exception& e) {
    return fail(app, e.what());
  }
  while (next_ < lines_.size()) {
    std::istringstream in(lines_[next_++]);
    std::string cmd;
    if (!(in >> cmd) || cmd[0] == '#') continue;
    std::string arg;
    std::getline(in >> std::ws, arg);
    try {
      const ScriptCommand* command = findScriptCommand(cmd);
      if (!command) throw ScriptFailure(fmt::format("unknown command `{}`", cmd));
      command->run(app, state_, arg);
    } catch (const std::exception& e) {
      return fail(app, e.what());
    }
    if (state_.repeatLine) {
      state_.repeatLine = false;
      --next_;
    }
    return;
  }
}

}  // namespace tl::editor
