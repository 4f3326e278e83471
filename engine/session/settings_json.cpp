#include "session/settings_json.h"

#include "scene/input_limits.h"
#include "session/session.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace tl::session {
namespace {

const lighting::SettingInfo& knownSetting(std::string_view name) {
  if (const lighting::SettingInfo* s = lighting::findSetting(name)) return *s;
  std::string known;
  for (const auto& s : lighting::settingsSchema()) known += fmt::format("{}{}", known.empty() ? "" : ", ", s.name);
  throw SessionError(fmt::format("unknown setting `{}` (known: {})", name, known));
}

// The JSON value in the setting's stored type, range-checked; throws std::invalid_argument.
double settingValue(const lighting::SettingInfo& s, const nlohmann::json& v) {
  using lighting::SettingType;
  double value = 0.0;
  switch (s.type) {
    case SettingType::Bool:
      if (!v.is_boolean()) throw std::invalid_argument(lighting::settingDomain(s));
      return v.get<bool>() ? 1.0 : 0.0;
    case SettingType::Enum:
      if (!v.is_string()) throw std::invalid_argument(lighting::settingDomain(s));
      return lighting::parseSetting(s, v.get<std::string>());
    case SettingType::UInt:
      if (!v.is_number()) throw std::invalid_argument(lighting::settingDomain(s));
      value = v.get<double>();
      break;
    case SettingType::Float:
      if (!v.is_number()) throw std::invalid_argument(lighting::settingDomain(s));
      value = double(v.get<float>());  // what the setting will hold
      break;
  }
  if (auto error = lighting::settingRangeError(s, value)) throw std::invalid_argument(*error);
  return value;
}

}  // namespace

nlohmann::json parseSettingsText(std::string_view text, const std::string& what) {
  try {
    scene::requireJsonDepth(text, what);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw SessionError(fmt::format("{} is not JSON: {}", what, e.what()));
  }
}

lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides) {
  if (!overrides.is_object()) throw SessionError("settings must be a JSON object of setting names and values");
  lighting::RenderSettings s = base;
  for (const auto& [key, value] : overrides.items()) {
    const lighting::SettingInfo& setting = knownSetting(key);
    try {
      setting.set(s, settingValue(setting, value));
    } catch (const std::invalid_argument& e) {
      std::string given = value.dump();
      if (given.size() > 60) given = given.substr(0, 60) + "...";
      throw SessionError(fmt::format("setting `{}` must be {}, not {}", key, e.what(), given));
    }
  }
  return s;
}

lighting::RenderSettings applySettingText(const lighting::RenderSettings& base, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw SessionError(fmt::format("--set takes NAME=VALUE (`twinlight settings` lists them), not `{}`", assignment));
  const std::string_view key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  const lighting::SettingInfo& setting = knownSetting(key);
  lighting::RenderSettings s = base;
  try {
    setting.set(s, lighting::parseSetting(setting, text));
  } catch (const std::invalid_argument& e) {
    throw SessionError(fmt::format("setting `{}` must be {}, not `{}`", key, e.what(), text));
  }
  return s;
}

nlohmann::json settingsJson(const lighting::RenderSettings& settings) {
  using lighting::SettingType;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& s : lighting::settingsSchema()) {
    const double v = s.get(settings);
    switch (s.type) {
      case SettingType::Bool: out[std::string(s.name)] = v != 0.0; break;
      case SettingType::Enum: out[std::string(s.name)] = lighting::formatSetting(s, v); break;
      case SettingType::UInt: out[std::string(s.name)] = uint64_t(v); break;
      case SettingType::Float: out[std::string(s.name)] = float(v); break;
    }
  }
  return out;
}

nlohmann::json readSettingsFile(const std::filesystem::path& file, bool allowList) {
  // A regular file within the size limit, JSON within the nesting limit (scene/input_limits.h).
  std::vector<uint8_t> bytes;
  try {
    bytes = scene::readRegularFile(file, scene::InputLimits::kMaxSettingsBytes);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  }
  const nlohmann::json j =
      parseSettingsText(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file.string());
  if (j.is_object() && j.contains("settings") && j["settings"].is_object()) return j["settings"];
  if (allowList && j.is_array()) return j;
  if (!j.is_object())
    throw SessionError(fmt::format("{}: expected a JSON object of settings{}", file.string(),
                                   allowList ? " or an array of configurations" : ""));
  return j;
}

}  // namespace tl::session
