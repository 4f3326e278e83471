// Script commands on render settings, as the Lighting panel changes them: set and expect a
// setting, presets, undo and redo, the render scale.
#include "script_commands.h"

#include "editor_app.h"
#include "settings_panel.h"
#include "session/settings_json.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

namespace tl::editor {
namespace {

void set(EditorApp& app, ScriptState&, const std::string& arg) {
  app.session().settings() = session::applySettingText(app.session().settings(), arg);
}

void expectSetting(EditorApp& app, ScriptState&, const std::string& arg) {
  std::istringstream a(arg);
  std::string name, want;
  a >> name >> want;
  const lighting::SettingInfo* s = lighting::findSetting(name);
  if (!s) throw ScriptFailure(fmt::format("unknown setting `{}`", name));
  const std::string have = lighting::formatSetting(*s, s->get(app.session().settings()));
  if (have != want) throw ScriptFailure(fmt::format("setting `{}` is {}, expected {}", name, have, want));
  fmt::print("setting {} = {}\n", name, have);
}

void undo(EditorApp& app, ScriptState&, const std::string&) {
  const std::string did = app.undo();
  if (did.empty()) throw ScriptFailure("nothing to undo");
  fmt::print("script: {}\n", did);
}

void redo(EditorApp& app, ScriptState&, const std::string&) {
  const std::string did = app.redo();
  if (did.empty()) throw ScriptFailure("nothing to redo");
  fmt::print("script: {}\n", did);
}

void preset(EditorApp& app, ScriptState&, const std::string& arg) { applyNamedPreset(app, arg); }

void savePreset(EditorApp& app, ScriptState&, const std::string& arg) {
  fmt::print("script: wrote preset {}\n", saveNamedPreset(app, arg).string());
}

void renderScale(EditorApp& app, ScriptState&, const std::string& arg) {
  app.settings().renderScale = std::clamp(std::stof(arg), 0.1f, 2.0f);
}

constexpr ScriptCommand kCommands[] = {
    {"set", set},
    {"expect-setting", expectSetting},
    {"undo", undo},
    {"redo", redo},
    {"preset", preset},
    {"save-preset", savePreset},
    {"render-scale", renderScale},
};

}  // namespace

std::span<const ScriptCommand> settingsScriptCommands() { return kCommands; }

}  // namespace tl::editor
