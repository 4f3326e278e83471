#include "settings_panel.h"

#include "editor_app.h"
#include "session/presets.h"
#include "session/settings_json.h"
#include "session/tune_space.h"
#include "settings.h"
#include "ui_helpers.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace tl::editor {
namespace {

using lighting::SettingInfo;
using lighting::SettingType;

std::string settingTooltip(const SettingInfo& s, const lighting::RenderSettings& settings, const lighting::SceneSize& sceneSize) {
  std::string text = fmt::format("{}\n{}{}{}", s.help, lighting::settingDomain(s), s.unit.empty() ? "" : ", in ",
                                 s.unit);
  if (s.flags & lighting::kSettingAuto)
    if (auto value = lighting::autoSettingValue(s, settings, sceneSize))
      text += fmt::format("\n0 = auto ({}): {:.3g} {} now", s.autoRule, *value, s.unit);
  text += s.history.empty() ? "\nchanging it restarts no history"
                            : fmt::format("\nchanging it restarts the history of: {}", s.history);
  return text;
}

// The widget for one setting; writes only a valid value back.
void settingWidget(const SettingInfo& s, lighting::RenderSettings& settings, const lighting::SceneSize& sceneSize) {
  const std::string label(s.name);
  const double value = s.get(settings);
  double next = value;
  switch (s.type) {
    case SettingType::Bool: {
      bool on = value != 0.0;
      if (ImGui::Checkbox(label.c_str(), &on)) next = on ? 1.0 : 0.0;
      break;
    }
    case SettingType::Enum: {
      if (ImGui::BeginCombo(label.c_str(), lighting::formatSetting(s, value).c_str())) {
        for (size_t i = 0; i < s.choices.size(); ++i)
          if (ImGui::Selectable(std::string(s.choices[i]).c_str(), double(i) == value)) next = double(i);
        ImGui::EndCombo();
      }
      break;
    }
    case SettingType::UInt: {
      if (s.flags & lighting::kSettingPow2) {
        if (ImGui::BeginCombo(label.c_str(), lighting::formatSetting(s, value).c_str())) {
          for (double v = s.min; v <= s.max; v *= 2.0)
            if (ImGui::Selectable(lighting::formatSetting(s, v).c_str(), v == value)) next = v;
          ImGui::EndCombo();
        }
      } else if (s.max - s.min <= 256.0) {
        int v = int(value);
        if (ImGui::SliderInt(label.c_str(), &v, int(s.min), int(s.max), fmt::format("%d {}", s.unit).c_str())) next = v;
      } else {
        uint32_t v = uint32_t(value);
        if (ImGui::InputScalar(label.c_str(), ImGuiDataType_U32, &v)) next = std::clamp(double(v), s.min, s.max);
      }
      break;
    }
    case SettingType::Float: {
      float v = float(value);
      const std::string unit = s.unit.empty() ? "" : " " + std::string(s.unit);
      if (s.flags & lighting::kSettingPow2) {  // a few rates (redeferredRate: 1, 0.5, 0.25)
        if (ImGui::BeginCombo(label.c_str(), lighting::formatSetting(s, value).c_str())) {
          for (double r = s.max; r >= s.min; r /= 2.0)
            if (ImGui::Selectable(lighting::formatSetting(s, r).c_str(), r == value)) next = r;
          ImGui::EndCombo();
        }
      } else if (s.flags & lighting::kSettingAuto) {
        // 0 shows "auto"; a drag starts from the automatic value (not from 0) and moves by a
        // hundredth of the value a pixel, so it feels the same in a millimetre model and a city.
        const float automatic = lighting::autoSettingValue(s, settings, sceneSize).value_or(0.0f);
        const float from = v > 0.0f ? v : automatic;
        const float speed = 0.01f * std::max(from, 1e-6f);
        float dragged = from;
        if (ImGui::DragFloat(label.c_str(), &dragged, speed, float(s.min), float(s.max),
                             v > 0.0f ? ("%.4g" + unit).c_str() : "auto") &&
            dragged != from)
          next = std::clamp(double(dragged), s.min, s.max);
      } else if (s.min > 0.0 && s.max / s.min >= 100.0) {
        if (ImGui::SliderFloat(label.c_str(), &v, float(s.min), float(s.max), ("%.3g" + unit).c_str(),
                               ImGuiSliderFlags_Logarithmic))
          next = v;
      } else if (s.max - s.min > 1000.0) {
        if (ImGui::DragFloat(label.c_str(), &v, 0.01f, float(s.min), float(s.max), ("%.4g" + unit).c_str()))
          next = std::clamp(double(v), s.min, s.max);
      } else {
        if (ImGui::SliderFloat(label.c_str(), &v, float(s.min), float(s.max), ("%.3g" + unit).c_str())) next = v;
      }
      if (next != value) next = double(float(next));
      break;
    }
  }
  trackItem("settings." + label);  // scripts reach the widget itself: click-ui settings.NAME
  tooltip(settingTooltip(s, settings, sceneSize).c_str());
  if (next != value && !lighting::settingRangeError(s, next)) s.set(settings, next);
}

// The widgets of the schema's settings that `shown` picks, in schema order, each leaving room
// for the longest name among them: a label is never cut off.
template <class Shown>
void settingGroup(lighting::RenderSettings& settings, const lighting::SceneSize& sceneSize, Shown shown) {
  float labelWidth = 0.0f;
  for (const SettingInfo& s : lighting::settingsSchema())
    if (shown(s)) labelWidth = std::max(labelWidth, ImGui::CalcTextSize(std::string(s.name).c_str()).x);
  ImGui::PushItemWidth(-(labelWidth + ImGui::GetStyle().ItemInnerSpacing.x + 1.0f));
  for (const SettingInfo& s : lighting::settingsSchema())
    if (shown(s) && !(s.flags & lighting::kSettingNoPanel)) settingWidget(s, settings, sceneSize);
  ImGui::PopItemWidth();
}

// Every path's reflections settings in one group (lighting::kSettingReflections), the shown
// path's first, with its switch on top: the RT on/off pair of a mirror is one click, and the
// other path's counterpart is beside it for a fair comparison. The switch puts the path's
// feature setting at its "off" value, and back at the value it had (its default if none).
void reflectionsGroup(lighting::RenderSettings& settings, const lighting::SceneSize& sceneSize,
                      const std::string& path) {
  static std::map<std::string, double, std::less<>> lastOn;  // per setting: the value the switch restores
  const auto reflections = [](const SettingInfo& s) { return (s.flags & lighting::kSettingReflections) != 0; };
  ImGui::SetNextItemOpen(true, ImGuiCond_Appearing);
  if (!ImGui::CollapsingHeader("reflections##settings.reflections")) return;
  std::vector<std::string_view> owners = {path};
  for (const SettingInfo& s : lighting::settingsSchema())
    if (reflections(s) && std::find(owners.begin(), owners.end(), s.owner) == owners.end()) owners.push_back(s.owner);
  for (std::string_view owner : owners) {
    const SettingInfo* feature = nullptr;
    for (const SettingInfo& s : lighting::settingsSchema())
      if (reflections(s) && s.owner == owner && (s.flags & lighting::kSettingFeature)) feature = &s;
    if (!feature) continue;  // a path without reflections (the shown one may have none)
    const double off = session::featureOffValue(*feature), value = feature->get(settings);
    bool on = value != off;
    if (on) lastOn[std::string(feature->name)] = value;
    ImGui::PushID(std::string(owner).c_str());
    if (ImGui::Checkbox(fmt::format("{} reflections{}", owner, owner == path ? " (this path)" : "").c_str(), &on)) {
      const auto it = lastOn.find(feature->name);
      feature->set(settings, on ? (it != lastOn.end() ? it->second : feature->defaultValue) : off);
    }
    ImGui::PopID();
    trackItem(fmt::format("reflections.{}", owner));
    tooltip(fmt::format("{}'s reflections on or off: off sets {} to {} (the SH specular shades every pixel), on "
                        "gives it back the value it had",
                        owner, feature->name, lighting::formatSetting(*feature, off))
                .c_str());
    ImGui::Indent();
    settingGroup(settings, sceneSize, [&](const SettingInfo& s) { return reflections(s) && s.owner == owner; });
    ImGui::Unindent();
  }
}

// The artist's presets: settings JSON files in the config directory's presets folder.
std::vector<std::filesystem::path> userPresets() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(presetDirectory(), ec))
    if (e.is_regular_file(ec) && e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

void applyPresetOrShow(EditorApp& app, const std::string& name) {
  try {
    applyNamedPreset(app, name);
  } catch (const std::exception& e) {
    app.showError(e.what());
  }
}

void presetRow(EditorApp& app) {
  auto& session = app.session();
  ImGui::SetNextItemWidth(170);
  if (ImGui::BeginCombo("Preset", fmt::format("{} presets", session.path()).c_str())) {
    for (const session::Preset& p : session::builtInPresets()) {
      if (p.path != session.path()) continue;
      if (ImGui::Selectable(p.name.c_str())) applyPresetOrShow(app, p.name);
      tooltip(p.description.c_str());
    }
    const auto mine = userPresets();
    if (!mine.empty()) ImGui::Separator();
    for (const auto& file : mine) {
      if (ImGui::Selectable(file.stem().string().c_str())) applyPresetOrShow(app, file.stem().string());
      tooltip(file.string().c_str());
    }
    ImGui::EndCombo();
  }
  tooltip("Fast / Balanced / Reference-like for this path (Balanced: the defaults), then your own.\n"
          "Ctrl+Z undoes a preset like any other change.");
  static char name[64] = "";
  ImGui::SetNextItemWidth(120);
  ImGui::InputTextWithHint("##presetName", "name", name, sizeof name);
  ImGui::SameLine();
  ImGui::BeginDisabled(name[0] == 0);
  if (ImGui::SmallButton("Save preset")) {
    try {
      app.notify(fmt::format("wrote preset {}", saveNamedPreset(app, name).string()));
    } catch (const std::exception& e) {
      app.showError(e.what());
    }
  }
  ImGui::EndDisabled();
  tooltip("Every setting as JSON in the presets folder: `twinlight render --settings FILE` and\n"
          "`twinlight compare --settings FILE` read it as it is");
}

// Tune for this view: a tune of the path in a child process; its presets join the Preset menu.
void tuneRow(EditorApp& app) {
  auto& session = app.session();
  static int budget = 0;  // 1x, 1.3x, 2x legacy's frame time
  static const char* budgets[] = {"1x-legacy", "1.3x-legacy", "2x-legacy"};
  TuneJob* job = app.tuneJob();
  const bool tunable = session.path() == "rt" || session.path() == "legacy";
  if (job && job->running()) {
    if (ImGui::SmallButton("Stop tuning")) app.stopTune();
    tooltip("Stops the tune (its measurements stay: asking again for this view resumes)");
    const std::string line = job->lastLine();
    ImGui::TextWrapped("tuning: %s", line.empty() ? "starting" : line.c_str());
    return;
  }
  ImGui::BeginDisabled(!tunable);
  if (ImGui::SmallButton("Tune for this view")) {
    TuneRequest request;
    request.budgets = {budgets[budget]};
    app.startTune(request);
  }
  ImGui::EndDisabled();
  tooltip(tunable ? "Searches this path's settings for the cheapest that keep the error of the best under the budget,\n"
                    "against the reference, at 320x180 from this camera (twinlight tune; a few minutes on a CPU).\n"
                    "The scene's file is tuned: save lighting edits first. The result appears under Preset."
                  : "Tuning is for the rt and legacy paths");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::Combo("budget", &budget, budgets, 3);
  tooltip("The frame time the preset may take: a multiple of the legacy path's, measured in the same run");
  if (!app.lastTuneSummary().empty()) ImGui::TextWrapped("tune: %s", app.lastTuneSummary().c_str());
}

}  // namespace

std::filesystem::path presetDirectory() { return configDirectory() / "presets"; }

void applyNamedPreset(EditorApp& app, const std::string& name) {
  auto& session = app.session();
  for (const session::Preset& p : session::builtInPresets())
    if (p.path == session.path() && p.name == name) {
      session.settings() = session::applyPreset(session.settings(), p);
      app.notify(fmt::format("preset {} for {}: {}", p.name, p.path, p.description));
      return;
    }
  const std::filesystem::path file = presetDirectory() / (name + ".json");
  if (!std::filesystem::exists(file))
    throw session::SessionError(fmt::format("no preset `{}` for {} (built in: Fast, Balanced, Reference-like; yours: {})",
                                            name, session.path(), presetDirectory().string()));
  session.settings() = session::loadPresetFile(file, session.settings());
  app.notify(fmt::format("preset {} from {}", name, file.string()));
}

std::filesystem::path saveNamedPreset(EditorApp& app, const std::string& name) {
  if (name.empty() || name.find_first_of("/\\") != std::string::npos || name.front() == '.')
    throw session::SessionError(fmt::format("a preset name is a plain file name, not `{}`", name));
  const std::filesystem::path file = presetDirectory() / (name + ".json");
  session::savePresetFile(file, app.session().settings());
  return file;
}

void settingsSection(EditorApp& app) {
  auto& session = app.session();
  lighting::RenderSettings& settings = session.settings();
  const lighting::SceneSize sceneSize = session.sceneSize();

  ImGui::Separator();
  ImGui::TextUnformatted("Render settings");
  static std::string pasteError;
  if (ImGui::SmallButton("Copy as JSON")) {
    nlohmann::json j = session::settingsJson(settings);
    ImGui::SetClipboardText(j.dump(2).c_str());
  }
  tooltip("Every setting as JSON: `twinlight render --settings FILE` (or capture, bench, compare) starts from it");
  ImGui::SameLine();
  if (ImGui::SmallButton("Paste JSON")) {
    const char* text = ImGui::GetClipboardText();
    try {
      nlohmann::json j = nlohmann::json::parse(text ? text : "");
      if (j.is_object() && j.contains("settings")) j = j["settings"];  // a manifest, bench JSON or report
      if (j.is_object()) j.erase("width"), j.erase("height");        // the viewport sets the size
      settings = session::applySettingsJson(settings, j);
      pasteError.clear();
    } catch (const std::exception& e) {
      pasteError = e.what();
    }
  }
  tooltip("Apply settings from JSON on the clipboard (a settings object, or a capture manifest, bench JSON or "
          "compare report holding one); the image size stays the viewport's");
  ImGui::SameLine();
  if (ImGui::SmallButton("Defaults")) {
    const lighting::RenderSettings defaults;
    for (const SettingInfo& s : lighting::settingsSchema())
      if (!(s.flags & lighting::kSettingNoPanel)) s.set(settings, s.get(defaults));
  }
  tooltip("Every setting back to its default (the image size stays the viewport's)");
  if (!pasteError.empty()) ImGui::TextWrapped("paste: %s", pasteError.c_str());
  presetRow(app);
  tuneRow(app);
  // Undo and redo of settings and lighting, one step per change of a schema entry (a drag is one).
  auto& history = app.editHistory();
  ImGui::BeginDisabled(!history.canUndo());
  if (ImGui::SmallButton("Undo")) app.undo();
  ImGui::EndDisabled();
  tooltip(history.canUndo() ? ("Undo " + history.undoLabel() + " (Ctrl+Z: the latest edit, albedo included)").c_str()
                            : "Nothing to undo: settings and lighting edits of this scene are undone here");
  ImGui::SameLine();
  ImGui::BeginDisabled(!history.canRedo());
  if (ImGui::SmallButton("Redo")) app.redo();
  ImGui::EndDisabled();
  tooltip(history.canRedo() ? ("Redo " + history.redoLabel() + " (Ctrl+Y)").c_str() : "Nothing to redo");

  // Owners in the order the schema first names them: common, then the paths; the reflections
  // group after common.
  std::vector<std::string_view> owners;
  for (const SettingInfo& s : lighting::settingsSchema())
    if (std::find(owners.begin(), owners.end(), s.owner) == owners.end()) owners.push_back(s.owner);
  for (std::string_view owner : owners) {
    const bool open = owner == "common" || owner == session.path();
    ImGui::SetNextItemOpen(open, ImGuiCond_Appearing);
    const std::string header = fmt::format("{}{}##settings.{}", owner, owner == session.path() ? " (this path)" : "", owner);
    if (ImGui::CollapsingHeader(header.c_str()))
      settingGroup(settings, sceneSize, [&](const SettingInfo& s) {
        return s.owner == owner && !(s.flags & lighting::kSettingReflections);
      });
    if (owner == "common") reflectionsGroup(settings, sceneSize, session.path());
  }
}

}  // namespace tl::editor
