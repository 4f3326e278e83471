// What `twinlight tune` searches: the settings the schema flags kSettingTune for a lighting path
// (its own and the common ones), each with a few candidate values derived from its default and
// range, and a population of configurations drawn from them by a seeded generator.
#pragma once

#include "lighting/common/render_settings.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tl::session {

struct TunableSetting {
  const lighting::SettingInfo* info = nullptr;
  std::vector<double> candidates;  // stored values (a switch: 0 and 1), the default among them
};

// A switch: both values. A number: its default times 1/4, 1/2, 1, 2 and 4 within the range
// (whole numbers rounded, powers of two kept so), and the range's minimum where that is 0 (the
// value that turns many settings off). A default of 0: 0 and 1, 2, 4, 8 within the range.
std::vector<double> candidateValues(const lighting::SettingInfo& setting);

// The tunable settings `path` reads: those it owns and the common ones, but a common one whose
// history column names only other paths; in schema order.
std::vector<TunableSetting> tunableSettings(std::string_view path);

// The value that leaves a kSettingFeature setting's feature out: false, or the range's minimum
// (maximum with kSettingOffAtMax).
double featureOffValue(const lighting::SettingInfo& setting);

// One configuration: a name and its overrides of the base settings, typed as settings JSON
// ({"rtHalfRays": true, "rtCachePaths": 1024}); {} is the path's defaults.
struct TuneConfig {
  std::string name;
  nlohmann::json overrides = nlohmann::json::object();
};

// `count` distinct configurations: the defaults first, then each setting moved to another of
// its candidates with a probability drawn per configuration (1/8, 1/4 or 1/2), by a 64-bit
// generator seeded with `seed` (the same population for the same seed on any machine). Named
// "c000", "c001", ...
std::vector<TuneConfig> samplePopulation(const std::vector<TunableSetting>& space, uint32_t count, uint64_t seed);

// The override's value as JSON typed as the schema types it (true, 1024, 0.25).
nlohmann::json settingJsonValue(const lighting::SettingInfo& setting, double value);

}  // namespace tl::session
