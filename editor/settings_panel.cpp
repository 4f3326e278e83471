#include "settings_panel.h"

#include "editor_app.h"
#include "session/settings_json.h"
#include "ui_helpers.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace tl::editor {
namespace {

using lighting::SettingInfo;
using lighting::SettingType;

std::string settingTooltip(const SettingInfo& s, const lighting::RenderSettings& settings, float sceneScale) {
  std::string text = fmt::format("{}\n{}{}{}", s.help, lighting::settingDomain(s), s.unit.empty() ? "" : ", in ",
                                 s.unit);
  if (s.flags & lighting::kSettingAuto)
    if (auto value = lighting::autoSettingValue(s.name, settings, sceneScale))
      text += fmt::format("\n0 = auto: {:.3g} {} now", *value, s.unit);
  text += s.history.empty() ? "\nchanging it restarts no history"
                            : fmt::format("\nchanging it restarts the history of: {}", s.history);
  return text;
}

// The widget for one setting; writes only a valid value back.
void settingWidget(const SettingInfo& s, lighting::RenderSettings& settings, float sceneScale) {
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
      if (s.flags & lighting::kSettingAuto) {
        if (ImGui::DragFloat(label.c_str(), &v, 0.01f, float(s.min), float(s.max), v > 0.0f ? ("%.3g" + unit).c_str() : "auto"))
          next = std::clamp(double(v), s.min, s.max);
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
  tooltip(settingTooltip(s, settings, sceneScale).c_str());
  if (next != value && !lighting::settingRangeError(s, next)) s.set(settings, next);
}

}  // namespace

void settingsSection(EditorApp& app) {
  auto& session = app.session();
  lighting::RenderSettings& settings = session.settings();
  const auto& b = session.scene().bounds;
  const float sceneScale = b.valid() ? float(glm::length(b.size())) : 1.0f;

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

  // Owners in the order the schema first names them: common, then the paths.
  std::vector<std::string_view> owners;
  for (const SettingInfo& s : lighting::settingsSchema())
    if (std::find(owners.begin(), owners.end(), s.owner) == owners.end()) owners.push_back(s.owner);
  for (std::string_view owner : owners) {
    const bool open = owner == "common" || owner == session.path();
    ImGui::SetNextItemOpen(open, ImGuiCond_Appearing);
    const std::string header = fmt::format("{}{}##settings.{}", owner, owner == session.path() ? " (this path)" : "", owner);
    if (!ImGui::CollapsingHeader(header.c_str())) continue;
    for (const SettingInfo& s : lighting::settingsSchema())
      if (s.owner == owner && !(s.flags & lighting::kSettingNoPanel)) settingWidget(s, settings, sceneScale);
  }
}

}  // namespace tl::editor
