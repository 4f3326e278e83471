// Speed against error: render the reference (cached on disk by everything that determines
// it) or read another renderer's image, run each lighting path for a fixed number of frames
// on the same scene, camera and light, and measure its per-pass GPU time and its error
// against the reference, as rendered and exposure-normalised. Thresholds on the errors make
// it a regression gate. Writes report.json (every figure), error maps (EXR + false-colour
// PNG) and report.html.
#pragma once

#include "metrics/image.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

// A regression gate's threshold: the compare fails when a path's `metric` exceeds `value`.
struct GateThreshold {
  std::string metric;  // canonical name, one of gateMetrics()
  double value = 0.0;
};
// The figures a gate can hold (errors: larger is worse), by their report.json names.
const std::vector<std::string>& gateMetrics();
// "relMSE=0.05,flip=0.1": metric names in any case. Throws SessionError naming what is wrong
// (an unknown metric, a figure where larger is better, a value that is not a number >= 0).
std::vector<GateThreshold> parseFailAbove(const std::string& spec);

// One measured configuration: a lighting path with settings changed from the session's.
struct CompareVariant {
  std::string name;            // shown in the report (unique)
  std::string path;            // lighting path
  nlohmann::json settings;     // RenderSettings overrides (session/settings_json.h), {} for none
};

struct CompareOptions {
  std::vector<std::string> paths;      // empty (and no variants): every available lighting path but the reference (debug views only by name)
  std::vector<CompareVariant> variants;  // measured after `paths` (compare --settings FILE)
  uint32_t referenceSpp = 256;         // multiple of 16
  // Render the reference until its relative standard error (session/reference_noise.h) is at
  // most this instead of a fixed sample count; referenceNoiseCap samples stop it if it is not
  // reached (the report says which).
  std::optional<double> referenceNoise;
  uint32_t referenceNoiseCap = NoiseTarget::kDefaultMaxSamples;
  uint32_t referenceBounces = lighting::RenderSettings{}.referenceBounces;  // the hard cap (Russian roulette ends paths first)
  // "full": referenceBounces scattering events; "same": 2 (direct light + one bounce, the
  // scope of the RT path's one-hit rays and of legacy's one-bounce cones).
  std::string scope = "full";
  uint32_t framesPerPath = 8;          // the last one is measured against the reference
  // The last this many frames are each measured and their noise-aware figures averaged, the
  // interval widened by their spread: a path's own noise (a firefly one frame holds) then
  // shows in the interval instead of deciding the figure. 1: the last frame alone.
  uint32_t errorFrames = 1;
  std::filesystem::path outDir = "out/compare";
  std::filesystem::path cacheDir;      // empty: $XDG_CACHE_HOME/twinlight/reference
  // Another renderer's image (linear RGB EXR, same camera and size) instead of the path
  // tracer: read and checked before anything renders (SessionError when unreadable, of
  // another size or holding non-finite values). Per-stage errors need the path tracer's
  // AO and irradiance and are left out.
  std::filesystem::path referenceFile;
  std::vector<GateThreshold> failAbove;  // report.json's "gate": the figures over their thresholds
};

// `what` and a fraction in [0,1], for a progress bar.
using Progress = std::function<void(const std::string& what, double fraction)>;

// The session must have its scene, view, light and size set. Returns report.json's content;
// report["gate"]["passed"] is false when any path exceeds a threshold of options.failAbove.
nlohmann::json runCompare(Session& session, const CompareOptions& options, const Progress& progress = {});

std::filesystem::path defaultReferenceCache();

// A read-back image as RGB floats (one channel repeated; alpha dropped).
metrics::Image rgbImage(const graph::Readback& image);

// The display encoding the tonemap pass applies, on the CPU (RGB): exposure, ACES, sRGB.
metrics::Image displayEncode(const metrics::Image& linear, float exposure);

}  // namespace tl::session
