#include "session/settings_json.h"

#include "scene/input_limits.h"
#include "session/session.h"
#include "shared/legacy.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <map>

namespace tl::session {
namespace {
// One setting by name: how to apply a JSON value to it (checked against its range first),
// and its value as JSON.
struct Field {
  std::function<void(lighting::RenderSettings&, const nlohmann::json&)> set;
  std::function<nlohmann::json(const lighting::RenderSettings&)> get;
};

template <class T>
std::function<nlohmann::json(const lighting::RenderSettings&)> getter(T lighting::RenderSettings::*member) {
  return [member](const lighting::RenderSettings& s) { return nlohmann::json(s.*member); };
}

// A bool field: true or false.
Field field(bool lighting::RenderSettings::*member) {
  return {[member](lighting::RenderSettings& s, const nlohmann::json& v) {
            if (!v.is_boolean()) throw std::invalid_argument("true or false");
            s.*member = v.get<bool>();
          },
          getter(member)};
}

// A whole-number field in [lo, hi], checked before the conversion (4294967297 would become 1).
Field field(uint32_t lighting::RenderSettings::*member, uint32_t lo, uint32_t hi) {
  return {[member, lo, hi](lighting::RenderSettings& s, const nlohmann::json& v) {
            const std::string range = fmt::format("a whole number from {} to {}", lo, hi);
            if (!v.is_number_integer()) throw std::invalid_argument(range);
            if (v.is_number_unsigned() ? v.get<uint64_t>() > hi || v.get<uint64_t>() < lo
                                       : v.get<int64_t>() < int64_t(lo) || v.get<int64_t>() > int64_t(hi))
              throw std::invalid_argument(range);
            s.*member = uint32_t(v.get<uint64_t>());
          },
          getter(member)};
}

// A float field: finite once stored as a float, and in [lo, hi].
Field field(float lighting::RenderSettings::*member, float lo, float hi) {
  return {[member, lo, hi](lighting::RenderSettings& s, const nlohmann::json& v) {
            const std::string range = fmt::format("a number from {:g} to {:g}", lo, hi);
            if (!v.is_number()) throw std::invalid_argument(range);
            const float f = float(v.get<double>());
            if (!std::isfinite(f) || f < lo || f > hi) throw std::invalid_argument(range);
            s.*member = f;
          },
          getter(member)};
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

// Every setting JSON may change, with the range its value must lie in (inclusive). Distances
// and radii of 0 mean "scaled to the scene" (frame_inputs.h); 1e6 m is their ceiling. The
// ceilings on counts bound the work a frame does (pre-trace steps, rays, frames, levels).
// [T13]'s settings schema will replace this table; until then it is where the ranges live.
const std::map<std::string, Field>& fields() {
  using S = lighting::RenderSettings;
  constexpr float kDistance = 1e6f;
  static const std::map<std::string, Field> table = {
      {"shadowMapSize", field(&S::shadowMapSize, 64, 8192)},
      {"softShadows", field(&S::softShadows)},
      {"pcssMaxRadiusTexels", field(&S::pcssMaxRadiusTexels, 0.0f, 64.0f)},
      {"specularGi", field(&S::specularGi)},
      {"taa", field(&S::taa)},
      {"taaBlend", field(&S::taaBlend, 0.01f, 1.0f)},
      {"materials", materialModeField()},
      {"referenceBounces", field(&S::referenceBounces, 1, 64)},
      {"rtSimplifyRatio", field(&S::rtSimplifyRatio, 0.01f, 1.0f)},
      {"rtAoRadius", field(&S::rtAoRadius, 0.0f, kDistance)},
      {"rtRayLength", field(&S::rtRayLength, 0.0f, kDistance)},
      {"rtBlendDistance", field(&S::rtBlendDistance, 0.0f, kDistance)},
      {"rtPretrace", field(&S::rtPretrace)},
      {"rtPretraceSteps", field(&S::rtPretraceSteps, 1, 256)},
      {"rtPretracePixels", field(&S::rtPretracePixels, 0.0f, 16384.0f)},
      {"rtThickness", field(&S::rtThickness, 0.0f, 1.0f)},
      {"rtMaxAccumFrames", field(&S::rtMaxAccumFrames, 1, 1024)},
      {"rtFireflyClamp", field(&S::rtFireflyClamp, 0.0f, 1e6f)},
      {"rtLumaRejection", field(&S::rtLumaRejection)},
      {"rtDisocclusionRays", field(&S::rtDisocclusionRays, 0, 64)},
      {"rtHitSky", field(&S::rtHitSky)},
      {"rtTwoRays", field(&S::rtTwoRays)},
      {"rtEmitterSampling", field(&S::rtEmitterSampling)},
      {"rtCullAngle", field(&S::rtCullAngle, 0.0f, 3.14159f)},
      {"rtCullMargin", field(&S::rtCullMargin, 0.0f, kDistance)},
      {"rtFarLegacy", field(&S::rtFarLegacy)},
      {"rtRefitTop", field(&S::rtRefitTop, 0, 65536)},
      {"rtRefitRandom", field(&S::rtRefitRandom, 0, 65536)},
      {"rtRefitVertexBudget", field(&S::rtRefitVertexBudget, 0, 1u << 30)},
      {"rtHalfRays", field(&S::rtHalfRays)},
      {"rtHalfResolution", field(&S::rtHalfResolution)},
      {"rtDenoise", field(&S::rtDenoise)},
      {"rtDenoiseRadius", field(&S::rtDenoiseRadius, 0.0f, kDistance)},
      {"rtScreenRadiance", field(&S::rtScreenRadiance)},
      {"legacyAoRadius", field(&S::legacyAoRadius, 0.0f, kDistance)},
      {"legacyAoThickness", field(&S::legacyAoThickness, 0.0f, 1.0f)},
      {"legacyAoSlices", field(&S::legacyAoSlices, 1, 16)},
      {"legacyAoSteps", field(&S::legacyAoSteps, 1, 64)},
      {"legacyAoDivisor", field(&S::legacyAoDivisor, 1, 2)},
      {"legacyConeDivisor", field(&S::legacyConeDivisor, 1, 4)},
      {"legacyVoxelResolution", field(&S::legacyVoxelResolution, 8, 256)},
      {"legacyLevel0Extent", field(&S::legacyLevel0Extent, 0.0f, kDistance)},
      {"legacyMaxLevels", field(&S::legacyMaxLevels, 1, shared::kLegacyMaxLevels)},
      {"legacyConeRange", field(&S::legacyConeRange, 0.0f, kDistance)},
      {"legacyConeStep", field(&S::legacyConeStep, 0.2f, 2.0f)},
      {"legacyScreenRadiance", field(&S::legacyScreenRadiance)},
      {"legacySettleFrames", field(&S::legacySettleFrames, 0, 64)},
      {"legacyPartialVoxels", field(&S::legacyPartialVoxels)},
      {"legacyAoFrames", field(&S::legacyAoFrames, 1, 64)},
  };
  return table;
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
    auto it = fields().find(key);
    if (it == fields().end()) {
      std::string known;
      for (const auto& [name, f] : fields()) known += (known.empty() ? "" : ", ") + name;
      throw SessionError(fmt::format("unknown setting `{}` (known: {})", key, known));
    }
    try {
      it->second.set(s, value);
    } catch (const std::invalid_argument& e) {
      std::string given = value.dump();
      if (given.size() > 60) given = given.substr(0, 60) + "...";
      throw SessionError(fmt::format("setting `{}` must be {}, not {}", key, e.what(), given));
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
