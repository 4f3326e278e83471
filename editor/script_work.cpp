// Script commands on the artist's work (editor/script.h lists them): opening and reloading,
// the unsaved-work question, the recovery offer, the window's title, what a scene change
// stopped, and a description of what a scene opened as, to compare ways of opening it.
#include "script_commands.h"

#include "editor_app.h"
#include "session/lighting_file.h"
#include "session/settings_json.h"

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_internal.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <chrono>
#include <fstream>
#include <sstream>

namespace tl::editor {
namespace {

// TEXT is held by `have`, or TEXT is `none` and there is nothing.
void expectHolds(const char* what, const std::optional<std::string>& have, const std::string& text) {
  if (text == "none") {
    if (have) throw ScriptFailure(fmt::format("expected no {}, but there is: {}", what, *have));
    return;
  }
  if (!have) throw ScriptFailure(fmt::format("expected {} holding `{}`, but there is none", what, text));
  if (have->find(text) == std::string::npos) throw ScriptFailure(fmt::format("{} is `{}`, without `{}`", what, *have, text));
}

std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n') c = ' ';
  return text;
}

void reload(EditorApp& app, ScriptState&, const std::string&) {
  if (!app.session().hasScene()) throw ScriptFailure("no scene to reload");
  app.reloadScene();
}

void closeWindow(EditorApp& app, ScriptState&, const std::string&) { app.askToQuit(); }

void expectQuestion(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& q = app.unsavedQuestion();
  expectHolds("question", q ? std::optional(oneLine(q->text)) : std::nullopt, arg);
  fmt::print("script: question: {}\n", q ? oneLine(q->text) : "none");
}

void expectUnsaved(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto w = app.unsavedWork();
  expectHolds("unsaved work", w.any() ? std::optional(w.describe()) : std::nullopt, arg);
  fmt::print("script: unsaved: {}\n", w.any() ? w.describe() : "none");
}

void expectTitle(EditorApp& app, ScriptState&, const std::string& arg) {
  if (app.windowTitle().find(arg) == std::string::npos)
    throw ScriptFailure(fmt::format("the window's title is `{}`, without `{}`", app.windowTitle(), arg));
  fmt::print("script: title: {}\n", app.windowTitle());
}

void expectRecovery(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& offer = app.recoveryOffer();
  expectHolds("recovery offer", offer ? std::optional(oneLine(offer->text)) : std::nullopt, arg);
  fmt::print("script: recovery: {}\n", offer ? oneLine(offer->text) : "none");
}

void autosaveEvery(EditorApp& app, ScriptState&, const std::string& arg) {
  const int seconds = std::atoi(arg.c_str());
  if (seconds < 1 || seconds > 60) throw ScriptFailure("autosave-every needs 1 to 60 seconds");
  app.settings().autosaveSeconds = seconds;
}

void expectStopped(EditorApp& app, ScriptState&, const std::string& arg) {
  std::string all;
  for (const auto& s : app.lastStopped()) all += (all.empty() ? "" : "; ") + s;
  expectHolds("stopped work", all.empty() ? std::nullopt : std::optional(all), arg);
  fmt::print("script: stopped: {}\n", all.empty() ? "none" : all);
}

void expectSun(EditorApp& app, ScriptState&, const std::string& arg) {
  const session::Lighting& l = app.session().lighting();
  const glm::dvec3 to = -glm::normalize(l.sunDirection);
  const std::string line = fmt::format("sun E {:.3f} {:.3f} {:.3f} towards {:.3f} {:.3f} {:.3f}", l.sunIrradiance.r,
                                       l.sunIrradiance.g, l.sunIrradiance.b, to.x, to.y, to.z);
  if (line.find(arg) == std::string::npos) throw ScriptFailure(fmt::format("the sun is `{}`, without `{}`", line, arg));
  fmt::print("script: {}\n", line);
}

void resize(EditorApp& app, ScriptState&, const std::string& arg) {
  int w = 0, h = 0;
  if (std::sscanf(arg.c_str(), "%d %d", &w, &h) != 2 || w < 320 || h < 240) throw ScriptFailure("resize needs W H (at least 320 240)");
  app.resizeWindow(w, h);
}

// Every window shown but the viewport itself, the menu bar, the status bar and a dialog (popup)
// stays off the viewport's area.
void expectViewportUncovered(EditorApp& app, ScriptState&, const std::string&) {
  const glm::vec2 min = app.viewportMin(), max = app.viewportMin() + app.viewportSize();
  for (ImGuiWindow* w : GImGui->Windows) {
    if (!w->WasActive || w->Hidden || w != w->RootWindow || std::string(w->Name) == "Viewport") continue;
    if (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_Popup | ImGuiWindowFlags_MenuBar | ImGuiWindowFlags_NoNav))
      continue;  // tooltips, dialogs, the menu bar and the status bar
    const float dx = std::min(max.x, w->Rect().Max.x) - std::max(min.x, w->Rect().Min.x);
    const float dy = std::min(max.y, w->Rect().Max.y) - std::max(min.y, w->Rect().Min.y);
    if (dx > 1.0f && dy > 1.0f) throw ScriptFailure(fmt::format("`{}` covers {:.0f} x {:.0f} px of the viewport", w->Name, dx, dy));
  }
  fmt::print("script: nothing covers the viewport ({:.0f} x {:.0f} px)\n", app.viewportSize().x, app.viewportSize().y);
}

nlohmann::json openedState(EditorApp& app) {
  auto& s = app.session();
  nlohmann::json j;
  j["scene"] = s.scene().path.filename().string();
  j["lighting"] = nlohmann::json::parse(session::lightingJson(s.lighting(), s.scene().path.parent_path()));
  nlohmann::json settings = session::settingsJson(s.settings());
  for (const lighting::SettingInfo& info : lighting::settingsSchema())
    if (info.flags & lighting::kSettingNoPanel) settings.erase(std::string(info.name));
  j["settings"] = settings;
  j["path"] = s.path();
  j["undo"] = app.editHistory().undoLabel();
  j["undoSteps"] = app.editHistory().steps();
  j["albedoUndo"] = s.albedo().canUndo();
  // The albedo overrides in use (saved or not), by mesh + material, for a walk that checks them.
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& e : s.albedo().entries())
    if (e.override) overrides[e.combination.label] = {e.override->r, e.override->g, e.override->b};
  j["overrides"] = overrides;
  j["orphans"] = s.albedo().orphanCount();
  j["unsaved"] = app.unsavedWork().describe();
  j["title"] = app.windowTitle();
  j["selected"] = app.selected() ? nlohmann::json(*app.selected()) : nlohmann::json(nullptr);
  j["selectedLight"] = app.selectedLight() ? nlohmann::json(*app.selectedLight()) : nlohmann::json(nullptr);
  const auto db = s.albedoDatabaseFile();
  j["albedoDatabase"] = db ? nlohmann::json(db->filename().string()) : nlohmann::json(nullptr);
  const session::View v = app.cameraView();
  j["camera"] = {{"position", {v.position.x, v.position.y, v.position.z}}, {"forward", {v.forward.x, v.forward.y, v.forward.z}}};
  j["exposureEv"] = s.exposureEv();
  return j;
}

void dumpState(EditorApp& app, ScriptState&, const std::string& arg) {
  std::istringstream words(arg);
  std::string dir, tag;
  if (!(words >> dir >> tag)) throw ScriptFailure("dump-state needs DIR TAG");
  if (!app.session().hasScene()) throw ScriptFailure("no scene to describe");
  std::filesystem::create_directories(dir);
  const std::filesystem::path file =
      std::filesystem::path(dir) / fmt::format("{}.{}.json", app.session().scene().path.filename().string(), tag);
  std::ofstream out(file);
  out << openedState(app).dump(2) << "\n";
  out.close();
  if (!out) throw ScriptFailure(fmt::format("cannot write {}", file.string()));
  fmt::print("script: wrote {}\n", file.string());
}

// tune-view BUDGET [WxH CANDIDATES RUNGS FRAMES SPP]: Lighting › Tune for this view, sized
// (the panel's button: 320x180, 81, 3, 32, 256).
void tuneView(EditorApp& app, ScriptState&, const std::string& arg) {
  std::istringstream words(arg);
  TuneRequest request;
  std::string budget;
  if (!(words >> budget)) throw ScriptFailure("tune-view needs a budget (1x-legacy)");
  request.budgets = {budget};
  std::string size;
  if (words >> size) {
    request.size = size;
    if (!(words >> request.candidates >> request.rungs >> request.frames >> request.spp))
      throw ScriptFailure("tune-view BUDGET WxH CANDIDATES RUNGS FRAMES SPP");
  }
  app.startTune(request);
  if (!app.tuneJob()) throw ScriptFailure("the tune did not start");
}

void waitTune(EditorApp&, ScriptState& state, const std::string& arg) {
  double seconds = 600.0;
  if (!arg.empty()) {
    std::istringstream in(arg);
    if (!(in >> seconds) || !(seconds > 0.0 && seconds <= 3600.0)) throw ScriptFailure("wait-tune takes seconds from 0 to 3600");
  }
  state.waitTune = true;
  state.tuneDeadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                              std::chrono::duration<double>(seconds));
}

void stopTune(EditorApp& app, ScriptState&, const std::string&) {
  if (!app.tuneJob()) throw ScriptFailure("stop-tune: no tune is running");
  app.stopTune();
  fmt::print("script: tune {}\n", app.lastTuneSummary());
}

void expectTune(EditorApp& app, ScriptState&, const std::string& arg) {
  if (app.lastTuneSummary().find(arg) == std::string::npos)
    throw ScriptFailure(fmt::format("the tune says `{}`, without `{}`", app.lastTuneSummary(), arg));
}

constexpr ScriptCommand kCommands[] = {
    {"tune-view", tuneView},
    {"wait-tune", waitTune},
    {"stop-tune", stopTune},
    {"expect-tune", expectTune},
    {"reload", reload},
    {"close-window", closeWindow},
    {"expect-question", expectQuestion},
    {"expect-unsaved", expectUnsaved},
    {"expect-title", expectTitle},
    {"expect-recovery", expectRecovery},
    {"autosave-every", autosaveEvery},
    {"expect-stopped", expectStopped},
    {"expect-sun", expectSun},
    {"resize", resize},
    {"expect-viewport-uncovered", expectViewportUncovered},
    {"dump-state", dumpState},
};

}  // namespace

std::span<const ScriptCommand> workScriptCommands() { return kCommands; }

}  // namespace tl::editor
