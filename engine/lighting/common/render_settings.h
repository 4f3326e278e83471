// The render settings, declared once. Each line of TL_RENDER_SETTINGS' groups (one per owner,
// in the owner's folder: common_settings.h, rt/rt_settings.h, legacy/legacy_settings.h,
// reference/reference_settings.h) is one setting: its C++ type, name, default, valid range,
// unit, owner (a lighting path, or `common`), the lighting paths whose history it resets,
// flags and a one-line help. From this list come the RenderSettings struct, the schema below
// (JSON and `--set` with range checks, the editor's panels, `twinlight settings`, the docs'
// reference table) and each path's history settings (the frame key's `settings` part): a new
// setting of the engine is one line in its group. A plugin declares its own settings in its
// folder (PluginSetting, below): they join the same schema.
#pragma once

#include "lighting/common/common_settings.h"
#include "lighting/legacy/legacy_settings.h"
#include "lighting/reference/reference_settings.h"
#include "lighting/rt/rt_settings.h"
#include "shared/material_mode.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace tl::lighting {

// Material override modes (shared/material_mode.h): every path and the reference shade the
// scene as authored, or all Lambertian with the authored base colour (diffuse) or 0.8 grey (clay).
enum class MaterialMode : uint32_t {
  Authored = shared::kMaterialsAuthored,
  Diffuse = shared::kMaterialsDiffuse,
  Clay = shared::kMaterialsClay,
};
inline constexpr MaterialMode kMaterialModes[] = {MaterialMode::Authored, MaterialMode::Diffuse, MaterialMode::Clay};
inline const char* materialModeName(MaterialMode m) {
  switch (m) {
    case MaterialMode::Diffuse: return "diffuse";
    case MaterialMode::Clay: return "clay";
    default: return "authored";
  }
}
inline std::optional<MaterialMode> parseMaterialMode(std::string_view name) {
  for (MaterialMode m : kMaterialModes)
    if (name == materialModeName(m)) return m;
  return std::nullopt;
}

// Setting flags (the `flags` column).
inline constexpr uint32_t kSettingPlain = 0;
inline constexpr uint32_t kSettingPow2 = 1u << 0;     // a power of two within the range (1/2, 1/4 for a number)
inline constexpr uint32_t kSettingAuto = 1u << 1;     // 0 means "derived from the scene or the image" (autoSettingValue)
inline constexpr uint32_t kSettingNoPanel = 1u << 2;  // set elsewhere (image size: --size, the render scale; probes)
// `twinlight tune` searches it (session/tune_space.h): a switch's two values, or its default
// times 1/4 .. 4 within the range. Windows of accumulation are not tuned: a still image's error
// cannot see what they cost (ghosts), so a tuner would always lengthen them.
inline constexpr uint32_t kSettingTune = 1u << 3;
// A feature a scene may not need: its switch off, or its range's minimum (its maximum with
// kSettingOffAtMax), leaves it out. `tune` tries its chosen presets without each.
inline constexpr uint32_t kSettingFeature = 1u << 4;
inline constexpr uint32_t kSettingOffAtMax = 1u << 5;
// A reflections setting: the editor's Lighting panel shows every path's together in its
// reflections group (the artist's RT on/off pair of a mirror), not in its owner's group. The
// owner's one flagged kSettingFeature too is that path's reflections switch.
inline constexpr uint32_t kSettingReflections = 1u << 6;

// X(type, name, default, min, max, unit, owner, resets history of, flags, help)
// Distances flagged kSettingAuto are "scaled to the scene" at 0 (see autoSettingValue).
// History: what a path's accumulated samples estimate restarts it; the ray pattern, the
// accumulation window, denoisers and update policies change only noise, weights or work
// (docs/design/frame-key.md). Redeferred shading changes how the composite
// applies light, downstream of every path's history: it resets none (its own light sums keep
// their own accumulation images).
// Each owner declares its group in its own folder; this list gathers the groups and names
// each one's owner (a lighting path's registered name, or `common`), in the schema's order.
#define TL_RENDER_SETTINGS(X)            \
  TL_COMMON_SETTINGS(X, "common")        \
  TL_REFERENCE_SETTINGS(X, "reference")  \
  TL_RT_SETTINGS(X, "rt")                \
  TL_LEGACY_SETTINGS(X, "legacy")

// The values of the settings plugins declare (PluginSetting), by the slot each registration
// got. NaN is a value never set, which stands for the setting's default: the defaults are
// known only once the plugins have registered, after these arrays may have been made.
inline constexpr size_t kMaxPluginSettings = 32;
using PluginSettingValues = std::array<double, kMaxPluginSettings>;
constexpr PluginSettingValues unsetPluginSettings() {
  PluginSettingValues v{};
  for (double& x : v) x = std::numeric_limits<double>::quiet_NaN();
  return v;
}

struct RenderSettings {
#define TL_SETTING_MEMBER(type, name, def, ...) type name = def;
  TL_RENDER_SETTINGS(TL_SETTING_MEMBER)
#undef TL_SETTING_MEMBER
  PluginSettingValues pluginValues = unsetPluginSettings();  // read through the plugin's PluginSetting
};

// A plugin setting's stored value: its slot's, or `fallback` (its default) where never set.
inline double pluginSettingValue(const RenderSettings& settings, uint32_t slot, double fallback) {
  const double v = settings.pluginValues[slot];
  return std::isnan(v) ? fallback : v;
}

enum class SettingType { Bool, UInt, Float, Enum };

// What automatic values derive from: the scene's size in its own units.
struct SceneSize {
  float diagonal = 1.0f;     // of its bounds (FrameConstants::sceneScale)
  float largestSide = 1.0f;  // of its bounds
};

// One setting as the schema knows it. `get`/`set` read and write it as a double (a bool as 0 or
// 1, the material mode as its index in `choices`); `set` takes a value already checked.
struct SettingInfo {
  std::string_view name;
  SettingType type;
  double defaultValue, min, max;
  std::string_view unit;
  std::string_view owner;    // "common" or a lighting path's name (a plugin's, for its own settings)
  // Space-separated names of the paths whose history it resets; a plugin's path adds itself
  // to an engine setting's with registerHistoryInputs, so this column never names a plugin.
  std::string_view history;
  uint32_t flags;
  std::string_view help;
  std::vector<std::string_view> choices;  // names of an enum's values, in order
  std::function<double(const RenderSettings&)> get;
  std::function<void(RenderSettings&, double)> set;
  // kSettingAuto: what 0 stands for, from the settings and the scene's extent, and that rule
  // in words ("the scene's extent / 6").
  float (*derive)(const RenderSettings&, const SceneSize&) = nullptr;
  std::string_view autoRule;

  // Its history column, or the path's own registerHistoryInputs, names `path`.
  bool resetsHistoryOf(std::string_view path) const;
};

// A plugin's setting, declared where the plugin lives (plugins/<name>/), as the engine's are in
// TL_RENDER_SETTINGS: the same columns, the same schema (JSON, `--set`, the editor's panel, the
// reference table, tune). Made from a static object in the plugin's .cpp, before main():
//   const PluginSetting<uint32_t> kRays{"bentSkyRays", 4, 1, 64, "rays", "bentsky", "bentsky",
//                                       kSettingPlain, "sky-visibility rays per pixel and frame"};
//   ... kRays.of(settings) ...
// Registering throws std::logic_error (a message at start-up) when the name is taken, the slots
// (kMaxPluginSettings) are used up, or the schema was already read: never a silent loss.
uint32_t registerPluginSetting(SettingInfo info);  // its slot in RenderSettings::pluginValues

template <class T>
class PluginSetting {
  static_assert(std::is_same_v<T, bool> || std::is_same_v<T, uint32_t> || std::is_same_v<T, float>,
                "a plugin's setting is a switch, a whole number or a number");

 public:
  PluginSetting(std::string_view name, T def, double min, double max, std::string_view unit, std::string_view owner,
                std::string_view history, uint32_t flags, std::string_view help)
      : slot_(registerPluginSetting({name, type(), double(def), min, max, unit, owner, history, flags, help, {}, {}, {}})),
        default_(def) {}

  // The value in `settings` (the default where it was never set), in the setting's type.
  T of(const RenderSettings& settings) const {
    const double v = pluginSettingValue(settings, slot_, double(default_));
    if constexpr (std::is_same_v<T, bool>) return v != 0.0;
    else return T(v);
  }

 private:
  static constexpr SettingType type() {
    if constexpr (std::is_same_v<T, bool>) return SettingType::Bool;
    else if constexpr (std::is_same_v<T, uint32_t>) return SettingType::UInt;
    else return SettingType::Float;
  }
  uint32_t slot_;
  T default_;
};

// A plugin's path whose history also restarts when these engine settings change (the
// materials, the light shadow maps, the ray length it borrows): declared by the plugin, so the
// engine's TL_RENDER_SETTINGS never names a plugin. Each name must be a setting, checked when
// the schema is first read (std::logic_error).
void registerHistoryInputs(std::string_view path, std::vector<std::string_view> settings);
struct HistoryInputsRegistrar {
  HistoryInputsRegistrar(std::string_view path, std::vector<std::string_view> settings) {
    registerHistoryInputs(path, std::move(settings));
  }
};

// Every setting, in declaration order.
const std::vector<SettingInfo>& settingsSchema();
const SettingInfo* findSetting(std::string_view name);

// Why `value` (already in the setting's C++ type: a whole number for an integer, 0/1 for a
// switch, an index for an enum) is not valid for the setting, or nothing when it is.
std::optional<std::string> settingRangeError(const SettingInfo& setting, double value);
// "2048", "true", "0.25", "clay": the value as text (for `--set`, tables and the UI).
std::string formatSetting(const SettingInfo& setting, double value);
// Parses `text` ("true", "2048", "0.5", "clay") into the setting's stored value, then checks
// the range; throws std::invalid_argument with what the setting takes.
double parseSetting(const SettingInfo& setting, std::string_view text);
// What the setting takes, in words: "a whole number in [256, 8192], a power of two".
std::string settingDomain(const SettingInfo& setting);

// The hash of the settings whose `history` column names `path` (0 when none does): the frame
// key's settings part for that path, so changing one of them restarts its history.
uint64_t historySettingsHash(const RenderSettings& settings, std::string_view path);

// Automatic values. A kSettingAuto setting at 0 stands for a value derived from the scene's
// extent (`sceneScale`: the diagonal of its bounds, in the scene's own units) or the image,
// never a length in metres: a scene authored in millimetres or kilometres gets the same
// picture. The derivations are the schema's (render_settings.cpp, one table; each setting's
// `autoRule` says it in words); a value the user sets keeps meaning metres.
// The value a kSettingAuto setting stands for at 0 (nothing for another setting).
std::optional<float> autoSettingValue(const SettingInfo& setting, const RenderSettings& settings, const SceneSize& scene);
std::optional<float> autoSettingValue(std::string_view name, const RenderSettings& settings, const SceneSize& scene);
// The settings a frame renders with: every automatic setting left at 0 replaced by its value.
RenderSettings resolveAutomatic(const RenderSettings& settings, const SceneSize& scene);

}  // namespace tl::lighting
