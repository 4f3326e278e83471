#include "session/tune_front.h"

#include <algorithm>
#include <cmath>

namespace tl::session {

bool significantlyFaster(const TunePoint& a, const TunePoint& b) { return a.timeHigh < b.timeLow; }

namespace {

bool lower(const metrics::NoiseAwareFigure& a, const metrics::NoiseAwareFigure& b) {
  return metrics::rank(a, b) == metrics::Ranking::Lower;
}

bool guardLower(const TunePoint& a, const TunePoint& b) { return a.guard && b.guard && lower(*a.guard, *b.guard); }

}  // namespace

bool significantlyMoreAccurate(const TunePoint& a, const TunePoint& b) { return lower(a.error, b.error) || guardLower(a, b); }

bool dominates(const TunePoint& a, const TunePoint& b) {
  if (significantlyFaster(b, a) || significantlyMoreAccurate(b, a)) return false;
  return significantlyFaster(a, b) || significantlyMoreAccurate(a, b);
}

std::vector<TunePoint> paretoFront(const std::vector<TunePoint>& points) {
  std::vector<TunePoint> front;
  for (const TunePoint& p : points)
    if (std::none_of(points.begin(), points.end(), [&](const TunePoint& q) { return dominates(q, p); }))
      front.push_back(p);
  std::stable_sort(front.begin(), front.end(), [](const TunePoint& a, const TunePoint& b) { return a.time < b.time; });
  return front;
}

namespace {

// Plain dominance on the measured values, for ranking survivors (where noise only decides
// which of two close points goes first, never whether a point is on the reported front).
bool dominatesByValue(const TunePoint& a, const TunePoint& b) {
  return a.time <= b.time && a.error.value <= b.error.value && (a.time < b.time || a.error.value < b.error.value);
}

}  // namespace

std::vector<TunePoint> survivors(const std::vector<TunePoint>& points, size_t keep, double timeLimit) {
  struct Ranked {
    const TunePoint* point;
    bool overBudget;        // significantly: its whole time interval above the limit
    bool significantFront;  // no point beats it beyond the noise
    size_t front;           // the plain fronts, peeled: 0 the first
  };
  std::vector<Ranked> ranked;
  for (const TunePoint& p : points) ranked.push_back({&p, p.timeLow > timeLimit, true, 0});
  for (Ranked& r : ranked)
    for (const Ranked& other : ranked)
      if (&other != &r && other.overBudget == r.overBudget && dominates(*other.point, *r.point)) r.significantFront = false;
  std::vector<bool> placed(ranked.size(), false);
  for (size_t level = 0, left = ranked.size(); left > 0; ++level) {
    std::vector<size_t> thisFront;
    for (size_t i = 0; i < ranked.size(); ++i) {
      if (placed[i]) continue;
      bool dominated = false;
      for (size_t j = 0; j < ranked.size() && !dominated; ++j)
        dominated = !placed[j] && j != i && ranked[j].overBudget == ranked[i].overBudget &&
                    ranked[j].significantFront == ranked[i].significantFront &&
                    dominatesByValue(*ranked[j].point, *ranked[i].point);
      if (!dominated) thisFront.push_back(i);
    }
    for (size_t i : thisFront) ranked[i].front = level, placed[i] = true;
    left -= thisFront.size();
  }
  // The significant front first (a cut does not hang on the timing noise of a busy machine);
  // within it the plain fronts, so cheap and accurate points both go on, not the most accurate
  // (and dearest) alone.
  std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
    if (a.overBudget != b.overBudget) return !a.overBudget;
    if (a.significantFront != b.significantFront) return a.significantFront;
    if (a.front != b.front) return a.front < b.front;
    if (a.point->error.value != b.point->error.value) return a.point->error.value < b.point->error.value;
    return a.point->name < b.point->name;
  });
  std::vector<TunePoint> kept;
  for (size_t i = 0; i < ranked.size() && kept.size() < keep; ++i) kept.push_back(*ranked[i].point);
  return kept;
}

std::optional<TunePoint> chooseWithinBudget(const std::vector<TunePoint>& points, double timeLimit) {
  const TunePoint* best = nullptr;
  for (const TunePoint& p : points)
    if (p.time <= timeLimit && std::isfinite(p.error.value) && (!best || p.error.value < best->error.value)) best = &p;
  if (!best) return std::nullopt;
  // The candidates: within the budget and within noise of the best error. Among them, the guard
  // must not be significantly worse than the best guard's: the most accurate point by the error
  // may itself be full of fireflies.
  std::vector<const TunePoint*> close;
  const TunePoint* bestGuard = nullptr;
  for (const TunePoint& p : points) {
    if (!(p.time <= timeLimit && std::isfinite(p.error.value)) || lower(best->error, p.error)) continue;
    close.push_back(&p);
    if (p.guard && (!bestGuard || p.guard->value < bestGuard->guard->value)) bestGuard = &p;
  }
  const TunePoint* chosen = nullptr;
  for (const TunePoint* p : close) {
    if (bestGuard && guardLower(*bestGuard, *p)) continue;
    if (!chosen || p->time < chosen->time || (p->time == chosen->time && p->name < chosen->name)) chosen = p;
  }
  return *chosen;
}

nlohmann::json pointJson(const TunePoint& p) {
  return {{"name", p.name},
          {"overrides", p.overrides},
          {"timeRatio", p.time},
          {"timeRatioInterval", {p.timeLow, p.timeHigh}},
          {"frameMs", p.frameMs},
          {"error", {{"value", p.error.value}, {"raw", p.error.raw}, {"low", p.error.low}, {"high", p.error.high}}},
          {"worstView", p.worstView},
          {"guard", p.guard ? nlohmann::json{{"value", p.guard->value}, {"raw", p.guard->raw}, {"low", p.guard->low}, {"high", p.guard->high}}
                            : nlohmann::json(nullptr)}};
}

}  // namespace tl::session
