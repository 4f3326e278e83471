#include "setting_aliases.h"

#include "session/session.h"
#include "session/settings_json.h"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

namespace tl::editor {
namespace {

const lighting::SettingInfo& schemaEntry(const char* name) {
  const lighting::SettingInfo* s = lighting::findSetting(name);
  if (!s) throw std::logic_error(fmt::format("setting alias names `{}`, which is not a setting", name));
  return *s;
}

// An enum's choices as words ("authored, diffuse or clay"), other domains as the schema says them.
std::string aliasDomain(const lighting::SettingInfo& s) {
  if (s.type != lighting::SettingType::Enum) return lighting::settingDomain(s);
  std::string names;
  for (size_t i = 0; i < s.choices.size(); ++i)
    names += fmt::format("{}{}", i == 0 ? "" : (i + 1 == s.choices.size() ? " or " : ", "), s.choices[i]);
  return names;
}

std::optional<double> number(std::string_view text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

bool sameChoice(std::string_view a, std::string_view b) {
  if (a == b) return true;
  const auto x = number(a), y = number(b);
  return x && y && *x == *y;
}

lighting::RenderSettings assign(const lighting::RenderSettings& settings, const char* name, const std::string& value) {
  return session::applySettingText(settings, fmt::format("{}={}", name, value));
}

// What --help shows for the option's value: "FLOAT", "true|false", "authored|diffuse|clay".
std::string valueName(const SettingAlias& a) {
  std::string names;
  if (a.kind == SettingAlias::Kind::Choice) {
    for (const auto& [choice, assignments] : a.choices) names += fmt::format("{}{}", names.empty() ? "" : "|", choice);
    return names;
  }
  const lighting::SettingInfo& s = schemaEntry(a.setting);
  switch (s.type) {
    case lighting::SettingType::Bool: return "true|false";
    case lighting::SettingType::UInt: return "UINT";
    case lighting::SettingType::Float: return "FLOAT";
    case lighting::SettingType::Enum: break;
  }
  for (std::string_view choice : s.choices) names += fmt::format("{}{}", names.empty() ? "" : "|", choice);
  return names;
}

}  // namespace

const std::vector<SettingAlias>& settingAliases() {
  using Kind = SettingAlias::Kind;
  static const std::vector<SettingAlias> aliases = {
      {Kind::Value, "materials", "materials"},
      {Kind::Flag, "hard-shadows", "softShadows", "false"},
      {Kind::Value, "rt-mesh-ratio", "rtSimplifyRatio"},
      {Kind::Choice, "rays-per-pixel", "rtHalfRays", nullptr,
       {{"1", {"rtHalfRays=false", "rtHalfResolution=false"}},
        {"0.5", {"rtHalfRays=true", "rtHalfResolution=false"}},
        {"0.25", {"rtHalfRays=false", "rtHalfResolution=true"}}},
       "rt path: 1, 0.5 (rtHalfRays: a checkerboard alternating each frame) or 0.25 (rtHalfResolution: one pixel of "
       "each 2x2)"},
      {Kind::Value, "pretrace", "rtPretrace"},
      {Kind::Value, "denoise", "rtDenoise"},
  };
  return aliases;
}

std::string settingAliasHelp(const SettingAlias& alias) {
  const lighting::SettingInfo& s = schemaEntry(alias.setting);
  switch (alias.kind) {
    case SettingAlias::Kind::Value:
      return fmt::format("{} ({}; --set {}=VALUE, default {})", s.help, aliasDomain(s), s.name,
                         lighting::formatSetting(s, s.defaultValue));
    case SettingAlias::Kind::Flag: return fmt::format("--set {}={} ({}: {})", s.name, alias.flagValue, s.name, s.help);
    case SettingAlias::Kind::Choice: break;
  }
  return alias.purpose;
}

void addSettingAliases(CLI::App& cmd, SettingAliasValues& values) {
  const auto& aliases = settingAliases();
  values.assign(aliases.size(), std::nullopt);
  for (size_t i = 0; i < aliases.size(); ++i) {
    const SettingAlias& a = aliases[i];
    const std::string name = std::string("--") + a.option;
    if (a.kind == SettingAlias::Kind::Flag)
      cmd.add_flag_callback(name, [&values, i, value = a.flagValue] { values[i] = value; }, settingAliasHelp(a));
    else
      cmd.add_option(name, values[i], settingAliasHelp(a))->type_name(valueName(a));
  }
}

void giveSettingAlias(SettingAliasValues& values, std::string_view option, std::string value) {
  const auto& aliases = settingAliases();
  if (values.empty()) values.assign(aliases.size(), std::nullopt);
  for (size_t i = 0; i < aliases.size(); ++i)
    if (aliases[i].option == option) return void(values[i] = std::move(value));
  throw std::logic_error(fmt::format("no setting alias --{}", option));
}

lighting::RenderSettings applySettingAliases(const lighting::RenderSettings& settings, const SettingAliasValues& values) {
  lighting::RenderSettings out = settings;
  const auto& aliases = settingAliases();
  for (size_t i = 0; i < aliases.size() && i < values.size(); ++i) {
    if (!values[i]) continue;
    const SettingAlias& a = aliases[i];
    const std::string& text = *values[i];
    if (a.kind == SettingAlias::Kind::Choice) {
      auto choice = std::find_if(a.choices.begin(), a.choices.end(), [&](const auto& c) { return sameChoice(c.first, text); });
      if (choice == a.choices.end()) {
        std::string names;
        for (size_t c = 0; c < a.choices.size(); ++c)
          names += fmt::format("{}{}", c == 0 ? "" : (c + 1 == a.choices.size() ? " or " : ", "), a.choices[c].first);
        throw session::SessionError(fmt::format("--{} must be {}, not `{}`", a.option, names, text));
      }
      for (const char* assignment : choice->second) out = session::applySettingText(out, assignment);
      continue;
    }
    const lighting::SettingInfo& s = schemaEntry(a.setting);
    try {
      lighting::parseSetting(s, text);
    } catch (const std::invalid_argument&) {
      throw session::SessionError(fmt::format("--{} must be {}, not `{}`", a.option, aliasDomain(s), text));
    }
    out = assign(out, a.setting, text);
  }
  return out;
}

}  // namespace tl::editor
