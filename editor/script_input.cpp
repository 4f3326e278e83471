// Script commands that act as a person's hands: clicks, the mouse wheel, keys and typing, and
// the panels they open; plus what the status bar and the labels show.
#include "script_commands.h"

#include "editor_app.h"
#include "ui_helpers.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <map>

namespace tl::editor {
namespace {

// A key by name: F1..F12, A..Z, 0..9, Enter, Escape, Tab, Backspace, Delete, Up, Down.
std::optional<int> keyCode(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0]))) return GLFW_KEY_A + (std::toupper(name[0]) - 'A');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0]))) return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F' && std::isdigit(static_cast<unsigned char>(name[1]))) {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  static const std::map<std::string, int> named = {{"Enter", GLFW_KEY_ENTER},   {"Escape", GLFW_KEY_ESCAPE},
                                                   {"Tab", GLFW_KEY_TAB},       {"Backspace", GLFW_KEY_BACKSPACE},
                                                   {"Delete", GLFW_KEY_DELETE}, {"Up", GLFW_KEY_UP},
                                                   {"Down", GLFW_KEY_DOWN}};
  auto it = named.find(name);
  return it == named.end() ? std::nullopt : std::optional<int>(it->second);
}

void click(EditorApp& app, ScriptState&, const std::string& arg) {
  float x, y;
  if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) throw ScriptFailure("click needs X Y");
  app.clickViewport({x, y});
}

void clickViewport(EditorApp& app, ScriptState&, const std::string& arg) {
  float u, v;
  if (std::sscanf(arg.c_str(), "%f %f", &u, &v) != 2) throw ScriptFailure("click-viewport needs U V");
  app.clickViewport(app.viewportMin() + app.viewportSize() * glm::vec2(u, v));
}

void mouseClick(EditorApp& app, ScriptState&, const std::string& arg) {
  float x, y;
  if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) throw ScriptFailure("mouse-click needs X Y");
  app.input().click({x, y});
}

void mouseWheel(EditorApp& app, ScriptState&, const std::string& arg) {
  float x, y, steps;
  if (std::sscanf(arg.c_str(), "%f %f %f", &x, &y, &steps) != 3) throw ScriptFailure("mouse-wheel needs X Y STEPS");
  app.input().push({InputEvent::Kind::Move, {x, y}});
  app.input().push({InputEvent::Kind::Wheel, {}, 0, false, {0.0f, steps}});
}

// A click (two for a double click) on a named control, once it is in view and uncovered.
void clickControl(EditorApp& app, ScriptState& s, const std::string& arg, int clicks) {
  const auto item = trackedItem(arg);
  if (!item) throw ScriptFailure(fmt::format("no control `{}` on screen", arg));
  if (!item->visible) {
    // Drawn but scrolled out of its window: scroll to it first, as a person would, and
    // click once it is in view (a click at its old place would land on another control).
    if (++s.scrollFrames > 10) throw ScriptFailure(fmt::format("control `{}` stays out of view", arg));
    scrollToItem(arg);
    s.repeatLine = true;
    return;
  }
  if (item->covered) {
    // Under another window: bring its own to the front first, as a person would (a
    // click where it is drawn would land on the window over it).
    if (++s.scrollFrames > 10) throw ScriptFailure(fmt::format("control `{}` stays covered by another window", arg));
    raiseItemWindow(arg);
    s.repeatLine = true;
    return;
  }
  s.scrollFrames = 0;
  const glm::vec2 centre = 0.5f * (item->min + item->max);
  for (int i = 0; i < clicks; ++i) app.input().click(centre);
}

void clickUi(EditorApp& app, ScriptState& s, const std::string& arg) { clickControl(app, s, arg, 1); }
void doubleClickUi(EditorApp& app, ScriptState& s, const std::string& arg) { clickControl(app, s, arg, 2); }

// [ctrl+][shift+]NAME: pressed and released within one frame, as a quick tap.
void key(EditorApp& app, ScriptState&, const std::string& arg) {
  std::string name = arg;
  std::vector<int> modifiers;
  for (auto [prefix, code] : {std::pair{"ctrl+", GLFW_KEY_LEFT_CONTROL}, std::pair{"shift+", GLFW_KEY_LEFT_SHIFT}})
    if (name.rfind(prefix, 0) == 0) modifiers.push_back(code), name = name.substr(std::strlen(prefix));
  const auto code = keyCode(name);
  if (!code) throw ScriptFailure(fmt::format("unknown key `{}`", name));
  for (int m : modifiers) app.input().push({InputEvent::Kind::Key, {}, m, true});
  app.input().push({InputEvent::Kind::Key, {}, *code, true});
  app.input().push({InputEvent::Kind::Key, {}, *code, false});
  for (int m : modifiers) app.input().push({InputEvent::Kind::Key, {}, m, false});
}

void type(EditorApp& app, ScriptState&, const std::string& arg) {
  for (unsigned char c : arg) app.input().push({InputEvent::Kind::Char, {}, int(c)});
}

void help(EditorApp& app, ScriptState&, const std::string& arg) { app.showHelp(arg == "on"); }
void browser(EditorApp& app, ScriptState&, const std::string& arg) { app.showBrowser(arg == "on"); }
void buffers(EditorApp& app, ScriptState&, const std::string& arg) { app.showBuffers(arg == "on"); }

void expectNotice(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& notices = app.notices();
  auto it = std::find_if(notices.rbegin(), notices.rend(), [&](auto& n) { return n.text.find(arg) != std::string::npos; });
  if (it == notices.rend()) throw ScriptFailure(fmt::format("no message containing `{}`", arg));
  fmt::print("script: message: {}\n", it->text);
}

void expectLabelsFit(EditorApp&, ScriptState&, const std::string&) {
  const auto& clipped = clippedLabels();
  if (!clipped.empty()) throw ScriptFailure(fmt::format("{} label(s) cut off, first: {}", clipped.size(), clipped.front()));
  fmt::print("script: every label fits\n");
}

constexpr ScriptCommand kCommands[] = {
    {"click", click},
    {"click-viewport", clickViewport},
    {"mouse-click", mouseClick},
    {"mouse-wheel", mouseWheel},
    {"click-ui", clickUi},
    {"double-click-ui", doubleClickUi},
    {"key", key},
    {"type", type},
    {"help", help},
    {"browser", browser},
    {"buffers", buffers},
    {"expect-notice", expectNotice},
    {"expect-labels-fit", expectLabelsFit},
};

}  // namespace

std::span<const ScriptCommand> inputScriptCommands() { return kCommands; }

}  // namespace tl::editor
