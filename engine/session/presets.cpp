#include "session/presets.h"

#include "session/image_io.h"
#include "session/session.h"
#include "session/settings_json.h"

#include <fmt/format.h>

#include <stdexcept>

namespace tl::session {

// What each preset changes, by the cost it removes or adds (docs/user-guide.md, "Presets"):
// Fast trades error for time, Reference-like time for error; Balanced is the defaults.
const std::vector<Preset>& builtInPresets() {
  static const std::vector<Preset> presets = {
      {"Fast", "direct", "a 1024 shadow map with hard (3x3 PCF) shadows",
       {{"shadowMapSize", "1024"}, {"softShadows", "false"}}},
      {"Balanced", "direct", "the defaults", {}},
      {"Reference-like", "direct", "a 4096 shadow map, TAA", {{"shadowMapSize", "4096"}, {"taa", "true"}}},
      {"Fast", "legacy", "a 32^3 clipmap, half-resolution AO, quarter-resolution cones, longer cone steps",
       {{"legacyVoxelResolution", "32"}, {"legacyAoDivisor", "2"}, {"legacyConeDivisor", "4"}, {"legacyConeStep", "1.5"}}},
      {"Balanced", "legacy", "the defaults", {}},
      {"Reference-like", "legacy", "a 128^3 clipmap, full-resolution AO and cones, short cone steps, more GTAO samples",
       {{"legacyVoxelResolution", "128"},
        {"legacyAoDivisor", "1"},
        {"legacyConeDivisor", "1"},
        {"legacyConeStep", "0.5"},
        {"legacyAoSlices", "4"},
        {"legacyAoSteps", "8"}}},
      {"Fast", "rt", "0.25 rays per pixel (half resolution), shorter pre-trace marches",
       {{"rtHalfResolution", "true"}, {"rtPretraceSteps", "8"}}},
      {"Balanced", "rt", "the defaults", {}},
      {"Reference-like", "rt", "2 rays per pixel on the full meshes, no culling, a longer accumulation",
       {{"rtTwoRays", "true"},
        {"rtSimplifyRatio", "1"},
        {"rtSimplifyError", "0"},
        {"rtCullAngle", "0"},
        {"rtMaxAccumFrames", "128"}}},
      {"Fast", "reference", "8 scattering events per path (biased: less light from long paths)",
       {{"referenceBounces", "8"}}},
      {"Balanced", "reference", "the defaults", {}},
      {"Reference-like", "reference", "4 samples per pixel a frame", {{"referenceSamplesPerFrame", "4"}}},
  };
  return presets;
}

lighting::RenderSettings applyPreset(const lighting::RenderSettings& base, const Preset& preset) {
  lighting::RenderSettings out = base;
  const lighting::RenderSettings defaults;
  for (const Preset& p : builtInPresets()) {
    if (p.path != preset.path) continue;
    for (const auto& [name, value] : p.values) {
      const lighting::SettingInfo* s = lighting::findSetting(name);
      if (!s) throw std::invalid_argument(fmt::format("preset {} / {}: no setting `{}`", p.path, p.name, name));
      s->set(out, s->get(defaults));
    }
  }
  for (const auto& [name, value] : preset.values) out = applySettingText(out, name + "=" + value);
  return out;
}

nlohmann::json presetSettingsJson(const Preset& preset) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : preset.values)
    out[name] = settingsJson(applySettingText(lighting::RenderSettings{}, name + "=" + value)).at(name);
  return out;
}

void savePresetFile(const std::filesystem::path& file, const lighting::RenderSettings& settings) {
  nlohmann::json j = settingsJson(settings);
  for (const lighting::SettingInfo& s : lighting::settingsSchema())
    if (s.flags & lighting::kSettingNoPanel) j.erase(std::string(s.name));  // the size is the viewport's
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  writeTextFile(file, j.dump(2) + "\n");
}

lighting::RenderSettings loadPresetFile(const std::filesystem::path& file, const lighting::RenderSettings& base) {
  nlohmann::json j = readSettingsFile(file);
  if (j.is_object()) j.erase("width"), j.erase("height");
  return applySettingsJson(base, j);
}

}  // namespace tl::session
