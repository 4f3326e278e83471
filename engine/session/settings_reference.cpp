#include "session/settings_reference.h"

#include "lighting/common/render_settings.h"
#include "lighting/lighting_path.h"
#include "session/tune_space.h"

#include <fmt/format.h>

namespace tl::session {
namespace {

using lighting::SettingInfo;
using lighting::SettingType;

std::string typeName(const SettingInfo& s) {
  switch (s.type) {
    case SettingType::Bool: return "switch";
    case SettingType::Enum: return "choice";
    case SettingType::UInt: return s.flags & lighting::kSettingPow2 ? "integer, power of two" : "integer";
    case SettingType::Float: break;
  }
  return "number";
}

std::string range(const SettingInfo& s) {
  switch (s.type) {
    case SettingType::Bool: return "true, false";
    case SettingType::Enum: {
      std::string names;
      for (auto c : s.choices) names += fmt::format("{}{}", names.empty() ? "" : ", ", c);
      return names;
    }
    default: break;
  }
  return fmt::format("{} .. {}", lighting::formatSetting(s, s.min), lighting::formatSetting(s, s.max));
}

std::string defaultText(const SettingInfo& s) {
  std::string text = lighting::formatSetting(s, s.defaultValue);
  if ((s.flags & lighting::kSettingAuto) && s.defaultValue == 0.0) text += " (auto)";
  return text;
}

// Every path whose history it restarts: the setting's own column and what the plugins declare.
std::string history(const SettingInfo& s) {
  std::string names;
  for (const std::string& path : lighting::lightingPathNames())
    if (s.resetsHistoryOf(path)) names += (names.empty() ? "" : " ") + path;
  return names.empty() ? "-" : names;
}

// What `twinlight tune` does with it: searches it, and tries presets without the feature it is.
std::string tuning(const SettingInfo& s) {
  if (!(s.flags & lighting::kSettingTune)) return "-";
  if (!(s.flags & lighting::kSettingFeature)) return "searched";
  return fmt::format("searched; a feature, off at {}", lighting::formatSetting(s, featureOffValue(s)));
}

}  // namespace

std::string settingsReferenceText() {
  std::string out = fmt::format("{:26} {:9} {:12} {:24} {:10} {:20} {}\n", "setting", "owner", "default", "range", "unit",
                                "restarts history of", "what it does");
  for (const SettingInfo& s : lighting::settingsSchema())
    out += fmt::format("{:26} {:9} {:12} {:24} {:10} {:20} {}\n", s.name, s.owner, defaultText(s), range(s),
                       s.unit.empty() ? "-" : std::string(s.unit),
                       history(s), s.help);
  return out;
}

std::string settingsReferenceMarkdown() {
  std::string out;
  out += "| setting | owner | type | default | range | unit | restarts the history of | tune | what it does |\n";
  out += "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const SettingInfo& s : lighting::settingsSchema())
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} | {} | {} |\n", s.name, s.owner, typeName(s), defaultText(s),
                       range(s), s.unit.empty() ? "-" : std::string(s.unit), history(s), tuning(s), s.help);
  return out;
}

}  // namespace tl::session
