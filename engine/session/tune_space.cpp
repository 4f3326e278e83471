#include "session/tune_space.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace tl::session {

using lighting::SettingInfo;
using lighting::SettingType;

namespace {

// Rounds a candidate to what the setting stores and keeps it only when the schema takes it.
void addCandidate(std::vector<double>& values, const SettingInfo& s, double v) {
  if (s.type == SettingType::UInt) v = std::round(v);
  if (s.type == SettingType::Float) v = double(float(v));
  if (lighting::settingRangeError(s, v)) return;
  if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
}

}  // namespace

std::vector<double> candidateValues(const SettingInfo& s) {
  std::vector<double> values;
  switch (s.type) {
    case SettingType::Bool: return {0.0, 1.0};
    case SettingType::Enum:
      for (size_t i = 0; i < s.choices.size(); ++i) values.push_back(double(i));
      return values;
    default: break;
  }
  addCandidate(values, s, s.defaultValue);
  if (s.defaultValue == 0.0) {
    for (double v : {1.0, 2.0, 4.0, 8.0}) addCandidate(values, s, v);
  } else {
    for (double f : {0.25, 0.5, 2.0, 4.0}) addCandidate(values, s, s.defaultValue * f);
    if (s.min == 0.0) addCandidate(values, s, 0.0);
  }
  std::sort(values.begin(), values.end());
  return values;
}

std::vector<TunableSetting> tunableSettings(std::string_view path) {
  std::vector<TunableSetting> space;
  for (const SettingInfo& s : lighting::settingsSchema()) {
    if (!(s.flags & lighting::kSettingTune) || (s.owner != path && s.owner != "common")) continue;
    // A common setting whose history names other paths but not this one is not read by it
    // (lightShadowMapSize: the paths that trace their shadows never build those maps).
    if (s.owner == "common" && !s.history.empty() && !s.resetsHistoryOf(path)) continue;
    space.push_back({&s, candidateValues(s)});
  }
  return space;
}

double featureOffValue(const SettingInfo& s) {
  if (s.type == SettingType::Bool) return 0.0;
  return (s.flags & lighting::kSettingOffAtMax) ? s.max : s.min;
}

nlohmann::json settingJsonValue(const SettingInfo& s, double value) {
  switch (s.type) {
    case SettingType::Bool: return value != 0.0;
    case SettingType::UInt: return uint64_t(value);
    case SettingType::Float: return float(value);
    case SettingType::Enum: return std::string(s.choices.at(size_t(value)));
  }
  return nullptr;
}

std::vector<TuneConfig> samplePopulation(const std::vector<TunableSetting>& space, uint32_t count, uint64_t seed) {
  // mt19937_64's sequence is fixed by the standard; the draws below use only its raw output
  // (the standard's distributions may differ between libraries).
  std::mt19937_64 random(seed);
  auto below = [&](uint64_t n) { return random() % n; };
  std::vector<TuneConfig> population{{"c000", nlohmann::json::object()}};
  std::set<std::string> seen{population[0].overrides.dump()};
  // Far more draws than needed before giving up: a space with few settings has few distinct
  // configurations.
  for (uint32_t attempt = 0; population.size() < count && attempt < count * 64u; ++attempt) {
    nlohmann::json overrides = nlohmann::json::object();
    // Each configuration moves a setting with probability 1/8, 1/4 or 1/2 (one of the three drawn
    // first): near neighbours of the defaults and far-flung mixes both.
    const uint64_t movesInEight = uint64_t(1) << below(3);
    for (const TunableSetting& t : space) {
      if (below(8) >= movesInEight || t.candidates.size() < 2) continue;
      std::vector<double> others;
      for (double v : t.candidates)
        if (v != t.info->defaultValue) others.push_back(v);
      overrides[std::string(t.info->name)] = settingJsonValue(*t.info, others[below(others.size())]);
    }
    if (!seen.insert(overrides.dump()).second) continue;
    population.push_back({fmt::format("c{:03}", population.size()), std::move(overrides)});
  }
  return population;
}

}  // namespace tl::session
