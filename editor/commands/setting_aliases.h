// Command-line short forms of render settings: `--rt-mesh-ratio 0.5` is
// `--set rtSimplifyRatio=0.5`, `--hard-shadows` is `--set softShadows=false`. Only the option's
// name and the setting it stands for are written here; its type, range, choices and help come
// from the settings schema (lighting/common/render_settings.h), so a range is stated once.
#pragma once

#include "session/settings_json.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tl::editor {

struct SettingAlias {
  enum class Kind {
    Value,   // --option VALUE sets `setting` to VALUE
    Flag,    // --option sets `setting` to `flagValue`
    Choice,  // --option CHOICE sets the settings `choices` names for it
  };
  Kind kind;
  const char* option;  // without the dashes: "rt-mesh-ratio"
  const char* setting;  // the setting it stands for (Value, Flag); the help's source
  const char* flagValue = nullptr;
  // Choice: each value the option takes (a number compares as a number: "0.50" is "0.5") and
  // the NAME=VALUE assignments it stands for.
  std::vector<std::pair<const char*, std::vector<const char*>>> choices = {};
  const char* purpose = nullptr;  // Choice: what the option is for (the settings' help follows)
};

// Every alias, in the order they are applied.
const std::vector<SettingAlias>& settingAliases();

// What each alias was given on the command line (the flag's value for a flag), by its index in
// settingAliases(); nothing where it was not given.
using SettingAliasValues = std::vector<std::optional<std::string>>;

// Adds every alias to `cmd`, writing into `values` (sized here; it must outlive the parse).
void addSettingAliases(CLI::App& cmd, SettingAliasValues& values);

// Gives the alias `--option` the value `value`, as if it were on the command line (`values`
// sized to settingAliases() first when empty).
void giveSettingAlias(SettingAliasValues& values, std::string_view option, std::string value);

// `settings` with each given alias applied in order, checked as `--set` checks a value;
// SessionError "--materials must be authored, diffuse or clay, not `plastic`" for a bad one.
lighting::RenderSettings applySettingAliases(const lighting::RenderSettings& settings, const SettingAliasValues& values);

// Help text of an alias: what its setting's schema says, the domain it takes and its setting's name.
std::string settingAliasHelp(const SettingAlias& alias);

}  // namespace tl::editor
