// compare's figures against the converged reference rather than the noisy one it rendered
// (metrics/noisy_reference.h): relMSE, relMSE_norm, FLIP and FLIP_norm with the reference's noise
// taken out of their expectation and a 95% interval each, the paths ranked only where their
// intervals do not overlap ("within noise" where they do), and the regression gate on the same
// intervals.
#pragma once

#include "metrics/image.h"
#include "metrics/noisy_reference.h"
#include "session/compare.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tl::session {

// The figures that get a noise-aware value and an interval.
const std::vector<std::string>& significanceMetrics();

// What the figures of one path are measured against: the reference, its per-pixel variance
// (reference.stderr squared; empty for another renderer's image: then every interval has no
// width), the exposure of the report's display images and the exposure normalisation.
struct NoisyReference {
  const metrics::Image& radiance;
  const metrics::Image& variance;
  float exposure = 1.0f;
  double normalisation = 1.0;
};

// {"relMSE": {"value", "raw", "low", "high"}, "relMSE_norm": ..., "FLIP": ..., "FLIP_norm": ...}.
nlohmann::json pathSignificance(const metrics::Image& test, const NoisyReference& reference);

metrics::NoiseAwareFigure figureFromJson(const nlohmann::json& figure);

// Several frames' pathSignificance as one: per metric the mean of the values (and raws), the
// interval's sides the mean of the frames' sides combined in quadrature with the frames' spread
// (Student's t at 95% over the standard error of the mean), with "frames" and "frameSpread" (the
// values' standard deviation). One frame is returned as it is.
nlohmann::json combineFrameSignificance(const std::vector<nlohmann::json>& frames);

// Per metric, the paths in order of value with `<` between neighbours whose intervals part and
// `~` between those within noise of each other ("rt < legacy ~ direct"), and every pair's verdict.
nlohmann::json rankPaths(const nlohmann::json& results);

// One figure against a gate's threshold: "passed", "failed" (the whole interval above it) or
// "within noise" (the interval holds it: neither is shown).
std::string gateVerdict(const metrics::NoiseAwareFigure& figure, double threshold);

// The regression gate (compare --fail-above): every path's figure against every threshold; a
// missing (non-finite) figure fails. A figure with an interval from the reference's noise fails
// only when its whole interval lies above the threshold and passes only when its whole interval
// lies at or below it; one whose interval holds the threshold is "within noise": the gate neither
// passes nor fails on the reference's noise ("passed" and "decided" false, exit code 5) until the
// reference has more samples. Figures against another renderer's image have no interval.
// {"failAbove", "failures", "withinNoise", "passed", "decided"}.
nlohmann::json evaluateGate(const nlohmann::json& results, const std::vector<GateThreshold>& thresholds);

}  // namespace tl::session
