#include "lighting/common/render_settings.h"

#include "lighting/common/frame_key.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace tl::lighting {
namespace {

template <class T>
constexpr SettingType settingType() {
  if constexpr (std::is_same_v<T, bool>) return SettingType::Bool;
  else if constexpr (std::is_same_v<T, uint32_t>) return SettingType::UInt;
  else if constexpr (std::is_same_v<T, float>) return SettingType::Float;
  else return SettingType::Enum;
}

template <class T>
std::vector<std::string_view> settingChoices() {
  if constexpr (std::is_same_v<T, MaterialMode>) {
    std::vector<std::string_view> names;
    for (MaterialMode m : kMaterialModes) names.push_back(materialModeName(m));
    return names;
  } else {
    return {};
  }
}

// An enum's stored value is its index among its choices; every other type is stored as is.
template <class T>
double toDouble(T v) {
  if constexpr (std::is_same_v<T, MaterialMode>) return double(uint32_t(v));
  else return double(v);
}
template <class T>
T fromDouble(double v) {
  if constexpr (std::is_same_v<T, bool>) return v != 0.0;
  else if constexpr (std::is_same_v<T, MaterialMode>) return MaterialMode(uint32_t(v));
  else return T(v);
}

bool isPowerOfTwo(double v) { return v > 0.0 && std::exp2(std::round(std::log2(v))) == v; }

// What each automatic setting stands for at 0: a share of the scene's extent e (the diagonal
// of its bounds) or of the image, so the same scene at any scale renders the same picture.
// No clamp in metres: a constant length is wrong for the first file authored in centimetres.
struct Derivation {
  std::string_view name;
  float (*derive)(const RenderSettings&, const SceneSize&);
  std::string_view rule;
};
float extent(const SceneSize& size) { return std::max(size.diagonal, 1e-30f); }
const Derivation kDerivations[] = {
    // AO sees occluders within a twentieth of the scene (Metro's SSAO reached about a metre in
    // rooms of tens of metres).
    {"rtAoRadius", [](const RenderSettings&, const SceneSize& e) { return 0.05f * extent(e); }, "5% of the scene's extent"},
    {"legacyAoRadius", [](const RenderSettings&, const SceneSize& e) { return 0.05f * extent(e); }, "5% of the scene's extent"},
    // Rays and cones as long as the scene is wide: nothing they could meet is out of reach.
    {"rtRayLength", [](const RenderSettings&, const SceneSize& e) { return extent(e); }, "the scene's extent"},
    {"legacyConeRange", [](const RenderSettings&, const SceneSize& e) { return extent(e); }, "the scene's extent"},
    // Twice the scene: every visible point is in the RT path's own GI.
    // A visible point's GI ray can reach what lies within its length of the view.
    {"rtCullMargin", [](const RenderSettings& s, const SceneSize& e) { return s.rtRayLength > 0.0f ? s.rtRayLength : extent(e); },
     "the ray length"},
    {"rtBlendDistance", [](const RenderSettings&, const SceneSize& e) { return 2.0f * extent(e); }, "twice the scene's extent"},
    // Metro's pass-1 radius relative to its world; the hit distances limit it further per pixel.
    {"rtDenoiseRadius", [](const RenderSettings&, const SceneSize& e) { return extent(e) / 6.0f; }, "the scene's extent / 6"},
    {"rtCacheCellSize", [](const RenderSettings&, const SceneSize& e) { return extent(e) / 1000.0f; }, "the scene's extent / 1000"},
    // The same share of the view at any resolution: 128 px at 360 lines.
    {"rtPretracePixels", [](const RenderSettings& s, const SceneSize&) { return std::max(16.0f, float(s.height) * (128.0f / 360.0f)); },
     "128 px per 360 lines of the image (at least 16)"},
    // The finest clipmap level holds the whole scene (its largest side, with the margin the
    // fit keeps for walls on the bounds): one level, its rooms' flood over all of it.
    {"legacyLevel0Extent", [](const RenderSettings&, const SceneSize& e) { return 1.02f * std::max(e.largestSide, 1e-30f); },
     "the scene's largest side (+2%): the finest level holds the scene"},
};

// What plugins registered before the schema was first read (function-local statics: plugins
// register from static initialisers, in whatever order the linker runs them).
struct PluginRegistrations {
  std::vector<SettingInfo> settings;
  std::vector<std::pair<std::string_view, std::vector<std::string_view>>> historyInputs;  // path, settings
  bool schemaRead = false;
};
PluginRegistrations& registrations() {
  static PluginRegistrations r;
  return r;
}

void refuseLateRegistration(std::string_view what) {
  if (registrations().schemaRead)
    throw std::logic_error(fmt::format("{} registered after the settings schema was read: register from a static object", what));
}

std::vector<SettingInfo> buildSchema() {
  std::vector<SettingInfo> schema;
#define TL_SETTING_INFO(type, name, def, lo, hi, unit, owner, history, flags, help)                              \
  schema.push_back({#name, settingType<type>(), toDouble<type>(def), double(lo), double(hi), unit, owner, history, \
                    flags, help, settingChoices<type>(),                                                           \
                    [](const RenderSettings& s) { return toDouble<type>(s.name); },                                \
                    [](RenderSettings& s, double v) { s.name = fromDouble<type>(v); }});
  TL_RENDER_SETTINGS(TL_SETTING_INFO)
#undef TL_SETTING_INFO
  // The plugins' own settings after the engine's, in the order the plugins' names sort (the
  // linker's order of static initialisers is not the same from one build to the next).
  std::vector<SettingInfo> plugins = registrations().settings;
  std::stable_sort(plugins.begin(), plugins.end(), [](const SettingInfo& a, const SettingInfo& b) { return a.owner < b.owner; });
  schema.insert(schema.end(), plugins.begin(), plugins.end());
  for (const auto& [path, names] : registrations().historyInputs)
    for (std::string_view name : names)
      if (std::none_of(schema.begin(), schema.end(), [&](const SettingInfo& s) { return s.name == name; }))
        throw std::logic_error(fmt::format("path `{}` restarts its history with `{}`, which is not a setting", path, name));
  // Each automatic setting has its derivation, and only those: checked once, loudly.
  for (const Derivation& d : kDerivations) {
    auto it = std::find_if(schema.begin(), schema.end(), [&](const SettingInfo& s) { return s.name == d.name; });
    if (it == schema.end() || !(it->flags & kSettingAuto))
      throw std::logic_error(fmt::format("automatic value for `{}`, which is not an automatic setting", d.name));
    it->derive = d.derive;
    it->autoRule = d.rule;
  }
  for (const SettingInfo& s : schema)
    if ((s.flags & kSettingAuto) && !s.derive)
      throw std::logic_error(fmt::format("automatic setting `{}` has no derivation", s.name));
  return schema;
}

}  // namespace

bool SettingInfo::resetsHistoryOf(std::string_view path) const {
  std::string_view rest = history;
  while (!rest.empty()) {
    const size_t space = rest.find(' ');
    if (rest.substr(0, space) == path) return true;
    rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
  }
  for (const auto& [p, names] : registrations().historyInputs)
    if (p == path && std::find(names.begin(), names.end(), name) != names.end()) return true;
  return false;
}

uint32_t registerPluginSetting(SettingInfo info) {
  refuseLateRegistration(fmt::format("setting `{}`", info.name));
  std::vector<SettingInfo>& settings = registrations().settings;
  const bool taken = std::any_of(settings.begin(), settings.end(), [&](const SettingInfo& s) { return s.name == info.name; });
  bool engines = false;
#define TL_SETTING_NAMED(type, setting, ...) engines = engines || info.name == #setting;
  TL_RENDER_SETTINGS(TL_SETTING_NAMED)
#undef TL_SETTING_NAMED
  if (taken || engines) throw std::logic_error(fmt::format("two settings are named `{}`", info.name));
  if (settings.size() == kMaxPluginSettings)
    throw std::logic_error(fmt::format("setting `{}`: the plugins have {} settings, the most there is room for", info.name,
                                       kMaxPluginSettings));
  if (info.flags & kSettingAuto)
    throw std::logic_error(fmt::format("setting `{}`: a plugin's setting cannot be automatic", info.name));
  const uint32_t slot = uint32_t(settings.size());
  const double fallback = info.defaultValue;
  const bool isSwitch = info.type == SettingType::Bool;
  info.get = [slot, fallback](const RenderSettings& s) { return pluginSettingValue(s, slot, fallback); };
  info.set = [slot, isSwitch](RenderSettings& s, double v) { s.pluginValues[slot] = isSwitch ? double(v != 0.0) : v; };
  settings.push_back(std::move(info));
  return slot;
}

void registerHistoryInputs(std::string_view path, std::vector<std::string_view> settings) {
  refuseLateRegistration(fmt::format("the history inputs of `{}`", path));
  registrations().historyInputs.emplace_back(path, std::move(settings));
}

const std::vector<SettingInfo>& settingsSchema() {
  static const std::vector<SettingInfo> schema = [] {
    std::vector<SettingInfo> built = buildSchema();
    registrations().schemaRead = true;
    return built;
  }();
  return schema;
}

const SettingInfo* findSetting(std::string_view name) {
  for (const SettingInfo& s : settingsSchema())
    if (s.name == name) return &s;
  return nullptr;
}

std::string settingDomain(const SettingInfo& s) {
  switch (s.type) {
    case SettingType::Bool: return "true or false";
    case SettingType::Enum: {
      std::string names;
      for (size_t i = 0; i < s.choices.size(); ++i)
        names += fmt::format("{}\"{}\"", i == 0 ? "" : (i + 1 == s.choices.size() ? " or " : ", "), s.choices[i]);
      return names;
    }
    case SettingType::UInt:
      return fmt::format("a whole number from {} to {}{}", uint64_t(s.min), uint64_t(s.max),
                         s.flags & kSettingPow2 ? ", a power of two" : "");
    case SettingType::Float: break;
  }
  return fmt::format("a number from {:g} to {:g}{}", s.min, s.max, s.flags & kSettingPow2 ? ", a power of two" : "");
}

std::optional<std::string> settingRangeError(const SettingInfo& s, double value) {
  const bool whole = s.type != SettingType::Float;
  if (!std::isfinite(value) || value < s.min || value > s.max || (whole && value != std::floor(value)) ||
      ((s.flags & kSettingPow2) && !isPowerOfTwo(value)))
    return settingDomain(s);
  return std::nullopt;
}

std::string formatSetting(const SettingInfo& s, double value) {
  switch (s.type) {
    case SettingType::Bool: return value != 0.0 ? "true" : "false";
    case SettingType::Enum: return std::string(size_t(value) < s.choices.size() ? s.choices[size_t(value)] : "?");
    case SettingType::UInt: return fmt::format("{}", uint64_t(value));
    case SettingType::Float: break;
  }
  return fmt::format("{:g}", float(value));
}

double parseSetting(const SettingInfo& s, std::string_view text) {
  double value = 0.0;
  switch (s.type) {
    case SettingType::Bool:
      if (text == "true" || text == "1") return 1.0;
      if (text == "false" || text == "0") return 0.0;
      throw std::invalid_argument(settingDomain(s));
    case SettingType::Enum:
      for (size_t i = 0; i < s.choices.size(); ++i)
        if (text == s.choices[i]) return double(i);
      throw std::invalid_argument(settingDomain(s));
    case SettingType::UInt:
    case SettingType::Float: {
      // The number as written, converted to the stored type before the range check: a float
      // setting keeps what a float can hold, an integer one must be whole.
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (ec != std::errc() || end != text.data() + text.size()) throw std::invalid_argument(settingDomain(s));
      if (s.type == SettingType::Float) value = double(float(value));
      break;
    }
  }
  if (auto error = settingRangeError(s, value)) throw std::invalid_argument(*error);
  return value;
}

uint64_t historySettingsHash(const RenderSettings& settings, std::string_view path) {
  KeyHasher hasher;
  bool any = false;
  for (const SettingInfo& s : settingsSchema())
    if (s.resetsHistoryOf(path)) hasher.add(s.get(settings)), any = true;
  return any ? hasher.done() : 0;
}

std::optional<float> autoSettingValue(const SettingInfo& setting, const RenderSettings& s, const SceneSize& scene) {
  if (!setting.derive) return std::nullopt;
  return setting.derive(s, scene);
}

std::optional<float> autoSettingValue(std::string_view name, const RenderSettings& s, const SceneSize& scene) {
  const SettingInfo* setting = findSetting(name);
  return setting ? autoSettingValue(*setting, s, scene) : std::nullopt;
}

RenderSettings resolveAutomatic(const RenderSettings& settings, const SceneSize& scene) {
  RenderSettings resolved = settings;
  for (const SettingInfo& s : settingsSchema())
    if (s.derive && s.get(settings) == 0.0) s.set(resolved, double(s.derive(settings, scene)));
  return resolved;
}

}  // namespace tl::lighting
