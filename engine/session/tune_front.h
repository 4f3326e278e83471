// Speed against error with both measured noisily: a configuration's frame time (its ratio to the
// baseline measured in the same run, with the spread of its frames) and its error against the
// reference (an interval from the reference's noise, session/compare_significance.h). One point
// dominates another only when it is no worse on both and significantly better on one: a front
// never drops a configuration on noise.
#pragma once

#include "metrics/noisy_reference.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tl::session {

struct TunePoint {
  std::string name;
  nlohmann::json overrides = nlohmann::json::object();
  // Frame time over the baseline's in the same run (the worst view's; medians of their frames),
  // and that ratio's 95% interval from the frames' spread (tune.cpp, unitPoint).
  double time = 0.0, timeLow = 0.0, timeHigh = 0.0;
  double frameMs = 0.0;              // its median GPU frame time (the worst view's)
  metrics::NoiseAwareFigure error;   // the worst view's, with its interval
  std::string worstView;             // where that error was measured
  // A second error that must not get significantly worse either (the worst view's): relMSE
  // rewards an image that loses light where that removes fireflies, FLIP does not.
  std::optional<metrics::NoiseAwareFigure> guard;
};

// a is significantly faster than b: their time intervals part.
bool significantlyFaster(const TunePoint& a, const TunePoint& b);
// a's error, or its guard, is significantly lower than b's: the intervals part.
bool significantlyMoreAccurate(const TunePoint& a, const TunePoint& b);
// a dominates b: not significantly slower nor less accurate, significantly better on one.
bool dominates(const TunePoint& a, const TunePoint& b);

// The points no other point dominates, in order of time.
std::vector<TunePoint> paretoFront(const std::vector<TunePoint>& points);

// Successive halving's cut: `keep` points, in rank order: points not significantly over
// `timeLimit` first (the others only when too few are left), then the significant front (what
// no point beats beyond the noise), each group by plain fronts peeled one at a time, each front
// by error, then name. Deterministic for equal input.
std::vector<TunePoint> survivors(const std::vector<TunePoint>& points, size_t keep, double timeLimit);

// Among the points within `timeLimit` (their median ratio) whose error is within noise of the
// best one's, the cheapest whose guard is not significantly worse than the best guard among
// them; nothing when none fits.
std::optional<TunePoint> chooseWithinBudget(const std::vector<TunePoint>& points, double timeLimit);

nlohmann::json pointJson(const TunePoint& p);

}  // namespace tl::session
