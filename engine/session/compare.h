// Speed against error: render the reference (cached on disk by everything that determines
// it), run each lighting path for a fixed number of frames on the same scene, camera and
// light, and measure its per-pass GPU time and its error against the reference. Writes
// report.json (every figure), error maps (EXR + false-colour PNG) and report.html.
#pragma once

#include "metrics/image.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tl::session {

// One measured configuration: a lighting path with settings changed from the session's.
struct CompareVariant {
  std::string name;            // shown in the report (unique)
  std::string path;            // lighting path
  nlohmann::json settings;     // RenderSettings overrides (session/settings_json.h), {} for none
};

struct CompareOptions {
  std::vector<std::string> paths;      // empty (and no variants): every available path except the reference
  std::vector<CompareVariant> variants;  // measured after `paths` (compare --settings FILE)
  uint32_t referenceSpp = 256;         // multiple of 16
  uint32_t referenceBounces = lighting::RenderSettings{}.referenceBounces;  // the hard cap (Russian roulette ends paths first)
  // "full": referenceBounces scattering events; "same": 2 (direct light + one bounce, the
  // scope of the RT path's one-hit rays and of legacy's one-bounce cones).
  std::string scope = "full";
  uint32_t framesPerPath = 8;          // the last one is measured against the reference
  std::filesystem::path outDir = "out/compare";
  std::filesystem::path cacheDir;      // empty: $XDG_CACHE_HOME/twinlight/reference
};

// `what` and a fraction in [0,1], for a progress bar.
using Progress = std::function<void(const std::string& what, double fraction)>;

// The session must have its scene, view, light and size set. Returns report.json's content.
nlohmann::json runCompare(Session& session, const CompareOptions& options, const Progress& progress = {});

std::filesystem::path defaultReferenceCache();

// A read-back image as RGB floats (one channel repeated; alpha dropped).
metrics::Image rgbImage(const graph::Readback& image);

// The display encoding the tonemap pass applies, on the CPU (RGB): exposure, ACES, sRGB.
metrics::Image displayEncode(const metrics::Image& linear, float exposure);

}  // namespace tl::session
