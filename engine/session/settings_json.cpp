#include "session/settings_json.h"

#include "session/session.h"

#include <fmt/format.h>

#include <functional>
#include <map>

namespace tl::session {
namespace {

// One setting by name: how to apply a JSON value to it, and its value as JSON.
struct Field {
  std::function<void(lighting::RenderSettings&, const nlohmann::json&)> set;
  std::function<nlohmann::json(const lighting::RenderSettings&)> get;
};

template <class T>
Field field(T lighting::RenderSettings::*member) {
  auto set = [member](lighting::RenderSettings& s, const nlohmann::json& v) {
    if constexpr (std::is_same_v<T, bool>) {
      if (!v.is_boolean()) throw std::invalid_argument("true or false");
      s.*member = v.get<bool>();
    } else if constexpr (std::is_unsigned_v<T>) {
      if (!v.is_number_integer() || v.get<int64_t>() < 0) throw std::invalid_argument("a whole number >= 0");
      s.*member = T(v.get<int64_t>());
    } else {
      if (!v.is_number()) throw std::invalid_argument("a number");
      s.*member = v.get<T>();
    }
  };
  return {set, [member](const lighting::RenderSettings& s) { return nlohmann::json(s.*member); }};
}

// The material override mode by name: "authored", "diffuse" or "clay".
Field materialModeField() {
  auto set = [](lighting::RenderSettings& s, const nlohmann::json& v) {
    const auto mode = v.is_string() ? lighting::parseMaterialMode(v.get<std::string>()) : std::nullopt;
    if (!mode) throw std::invalid_argument("\"authored\", \"diffuse\" or \"clay\"");
    s.materials = *mode;
  };
  return {set, [](const lighting::RenderSettings& s) { return nlohmann::json(lighting::materialModeName(s.materials)); }};
}

const std::map<std::string, Field>& fields() {
  using S = lighting::RenderSettings;
  static const std::map<std::string, Field> table = {
      {"shadowMapSize", field(&S::shadowMapSize)},
      {"softShadows", field(&S::softShadows)},
      {"pcssMaxRadiusTexels", field(&S::pcssMaxRadiusTexels)},
      {"specularGi", field(&S::specularGi)},
      {"taa", field(&S::taa)},
      {"taaBlend", field(&S::taaBlend)},
      {"materials", materialModeField()},
      {"referenceBounces", field(&S::referenceBounces)},
      {"rtSimplifyRatio", field(&S::rtSimplifyRatio)},
      {"rtAoRadius", field(&S::rtAoRadius)},
      {"rtRayLength", field(&S::rtRayLength)},
      {"rtBlendDistance", field(&S::rtBlendDistance)},
      {"rtPretrace", field(&S::rtPretrace)},
      {"rtPretraceSteps", field(&S::rtPretraceSteps)},
      {"rtPretracePixels", field(&S::rtPretracePixels)},
      {"rtThickness", field(&S::rtThickness)},
      {"rtMaxAccumFrames", field(&S::rtMaxAccumFrames)},
      {"rtFireflyClamp", field(&S::rtFireflyClamp)},
      {"rtLumaRejection", field(&S::rtLumaRejection)},
      {"rtDisocclusionRays", field(&S::rtDisocclusionRays)},
      {"rtHitSky", field(&S::rtHitSky)},
      {"rtTwoRays", field(&S::rtTwoRays)},
      {"rtEmitterSampling", field(&S::rtEmitterSampling)},
      {"rtCullAngle", field(&S::rtCullAngle)},
      {"rtCullMargin", field(&S::rtCullMargin)},
      {"rtFarLegacy", field(&S::rtFarLegacy)},
      {"rtRefitTop", field(&S::rtRefitTop)},
      {"rtRefitRandom", field(&S::rtRefitRandom)},
      {"rtRefitVertexBudget", field(&S::rtRefitVertexBudget)},
      {"rtHalfRays", field(&S::rtHalfRays)},
      {"rtHalfResolution", field(&S::rtHalfResolution)},
      {"rtDenoise", field(&S::rtDenoise)},
      {"rtDenoiseRadius", field(&S::rtDenoiseRadius)},
      {"rtScreenRadiance", field(&S::rtScreenRadiance)},
      {"legacyAoRadius", field(&S::legacyAoRadius)},
      {"legacyAoThickness", field(&S::legacyAoThickness)},
      {"legacyAoSlices", field(&S::legacyAoSlices)},
      {"legacyAoSteps", field(&S::legacyAoSteps)},
      {"legacyAoDivisor", field(&S::legacyAoDivisor)},
      {"legacyConeDivisor", field(&S::legacyConeDivisor)},
      {"legacyVoxelResolution", field(&S::legacyVoxelResolution)},
      {"legacyLevel0Extent", field(&S::legacyLevel0Extent)},
      {"legacyMaxLevels", field(&S::legacyMaxLevels)},
      {"legacyConeRange", field(&S::legacyConeRange)},
      {"legacyConeStep", field(&S::legacyConeStep)},
      {"legacyScreenRadiance", field(&S::legacyScreenRadiance)},
      {"legacySettleFrames", field(&S::legacySettleFrames)},
      {"legacyPartialVoxels", field(&S::legacyPartialVoxels)},
      {"legacyAoFrames", field(&S::legacyAoFrames)},
  };
  return table;
}

}  // namespace

lighting::RenderSettings applySettingsJson(const lighting::RenderSettings& base, const nlohmann::json& overrides) {
  if (!overrides.is_object()) throw SessionError("settings must be a JSON object of setting names and values");
  lighting::RenderSettings s = base;
  for (const auto& [key, value] : overrides.items()) {
    auto it = fields().find(key);
    if (it == fields().end()) {
      std::string known;
      for (const auto& [name, f] : fields()) known += (known.empty() ? "" : ", ") + name;
      throw SessionError(fmt::format("unknown setting `{}` (known: {})", key, known));
    }
    try {
      it->second.set(s, value);
    } catch (const std::invalid_argument& e) {
      throw SessionError(fmt::format("setting `{}` must be {}, not {}", key, e.what(), value.dump()));
    }
  }
  return s;
}

nlohmann::json settingsJson(const lighting::RenderSettings& settings) {
  nlohmann::json out = {{"width", settings.width}, {"height", settings.height}};
  for (const auto& [name, f] : fields()) out[name] = f.get(settings);
  return out;
}

}  // namespace tl::session
