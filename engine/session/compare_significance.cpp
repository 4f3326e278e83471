#include "session/compare_significance.h"

#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "session/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tl::session {
namespace {

nlohmann::json toJson(const metrics::NoiseAwareFigure& f) {
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"value", finite(f.value)}, {"raw", finite(f.raw)}, {"low", finite(f.low)}, {"high", finite(f.high)}};
}

// SIMEX draws per noise level for the FLIP figures (each a FLIP of the whole image).
constexpr int kFlipDraws = 2;

}  // namespace

const std::vector<std::string>& significanceMetrics() {
  static const std::vector<std::string> names = {"relMSE", "relMSE_norm", "FLIP", "FLIP_norm"};
  return names;
}

nlohmann::json pathSignificance(const metrics::Image& test, const NoisyReference& ref) {
  nlohmann::json out;
  out["relMSE"] = toJson(metrics::relMseNoiseAware(test, ref.radiance, ref.variance));
  out["relMSE_norm"] = toJson(metrics::relMseNoiseAware(test, ref.radiance, ref.variance, ref.normalisation));
  // FLIP compares display images: the reference's noise goes through the tone curve, so its
  // share is found by simulation (SIMEX), the noisy reference made noisier twice over.
  for (const auto& [name, exposure] : {std::pair<const char*, float>{"FLIP", ref.exposure},
                                       std::pair<const char*, float>{"FLIP_norm", float(ref.normalisation)}}) {
    const metrics::Image testDisplay = displayEncode(test, exposure);
    const float e = exposure;
    out[name] = toJson(metrics::simexNoiseAware(
        ref.radiance, ref.variance,
        [&testDisplay, e](const metrics::Image& r) { return metrics::flipLdr(testDisplay, displayEncode(r, e)).value; },
        kFlipDraws));
  }
  return out;
}

metrics::NoiseAwareFigure figureFromJson(const nlohmann::json& f) {
  auto get = [&](const char* k) {
    return f.contains(k) && f[k].is_number() ? f[k].get<double>() : std::numeric_limits<double>::infinity();
  };
  return {get("value"), get("raw"), get("low"), get("high")};
}

namespace {

// Student's t at 97.5% for n - 1 degrees of freedom (n >= 2); the normal's 1.96 beyond 30.
double studentT975(size_t n) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                 2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                 2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045};
  const size_t dof = n - 1;
  return dof >= 1 && dof <= 29 ? table[dof - 1] : 1.96;
}

}  // namespace

nlohmann::json combineFrameSignificance(const std::vector<nlohmann::json>& frames) {
  if (frames.size() <= 1) return frames.empty() ? nlohmann::json::object() : frames.front();
  nlohmann::json out = nlohmann::json::object();
  const double n = double(frames.size());
  for (const std::string& metric : significanceMetrics()) {
    double value = 0.0, raw = 0.0, below = 0.0, above = 0.0;
    std::vector<double> values;
    for (const auto& f : frames) {
      const metrics::NoiseAwareFigure fig = figureFromJson(f.value(metric, nlohmann::json::object()));
      values.push_back(fig.value);
      value += fig.value / n, raw += fig.raw / n, below += (fig.value - fig.low) / n, above += (fig.high - fig.value) / n;
    }
    double variance = 0.0;
    for (double v : values) variance += (v - value) * (v - value) / (n - 1.0);
    const double spread = std::sqrt(variance), frameSide = studentT975(frames.size()) * spread / std::sqrt(n);
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    out[metric] = {{"value", finite(value)},
                   {"raw", finite(raw)},
                   {"low", finite(value - std::hypot(below, frameSide))},
                   {"high", finite(value + std::hypot(above, frameSide))},
                   {"frames", frames.size()},
                   {"frameSpread", finite(spread)}};
  }
  return out;
}

nlohmann::json rankPaths(const nlohmann::json& results) {
  nlohmann::json out = nlohmann::json::object();
  for (const std::string& metric : significanceMetrics()) {
    struct Entry {
      std::string path;
      metrics::NoiseAwareFigure figure;
    };
    std::vector<Entry> entries;
    for (const auto& r : results)
      if (r.contains("significance") && r["significance"].contains(metric))
        entries.push_back({r["path"].get<std::string>(), figureFromJson(r["significance"][metric])});
    if (entries.empty()) continue;
    std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.figure.value < b.figure.value; });
    std::string order = entries[0].path;
    for (size_t i = 1; i < entries.size(); ++i)
      order += fmt::format(" {} {}", metrics::rank(entries[i - 1].figure, entries[i].figure) == metrics::Ranking::Lower ? "<" : "~",
                           entries[i].path);
    nlohmann::json pairs = nlohmann::json::array();
    for (size_t i = 0; i < entries.size(); ++i)
      for (size_t j = i + 1; j < entries.size(); ++j) {
        const metrics::Ranking r = metrics::rank(entries[i].figure, entries[j].figure);
        pairs.push_back({{"a", entries[i].path}, {"b", entries[j].path},
                         {"verdict", r == metrics::Ranking::Lower    ? entries[i].path + " lower"
                                     : r == metrics::Ranking::Higher ? entries[j].path + " lower"
                                                                     : "within noise"}});
      }
    out[metric] = {{"order", order}, {"pairs", pairs}};
  }
  return out;
}

std::string gateVerdict(const metrics::NoiseAwareFigure& figure, double threshold) {
  switch (metrics::againstThreshold(figure, threshold)) {
    case metrics::Threshold::Above: return "failed";
    case metrics::Threshold::Below: return "passed";
    default: return "within noise";
  }
}

// A figure with an interval is judged by it (gateVerdict); one without fails above its threshold.
nlohmann::json evaluateGate(const nlohmann::json& results, const std::vector<GateThreshold>& thresholds) {
  nlohmann::json limits = nlohmann::json::object(), failures = nlohmann::json::array(), withinNoise = nlohmann::json::array();
  for (const auto& t : thresholds) limits[t.metric] = t.value;
  for (const auto& r : results)
    for (const auto& t : thresholds) {
      if (r.contains("significance") && r["significance"].contains(t.metric)) {
        const nlohmann::json& f = r["significance"][t.metric];
        const std::string verdict = gateVerdict(figureFromJson(f), t.value);
        nlohmann::json entry = {{"path", r["path"]}, {"metric", t.metric}, {"value", f["value"]}, {"low", f["low"]},
                                {"high", f["high"]}, {"threshold", t.value}};
        if (verdict == "failed") failures.push_back(entry);
        else if (verdict == "within noise") withinNoise.push_back(entry);
        continue;
      }
      const nlohmann::json& figure = r[t.metric];
      if (figure.is_number() && figure.get<double>() <= t.value) continue;
      failures.push_back({{"path", r["path"]}, {"metric", t.metric}, {"value", figure}, {"threshold", t.value}});
    }
  return {{"failAbove", limits},
          {"failures", failures},
          {"withinNoise", withinNoise},
          {"passed", failures.empty() && withinNoise.empty()},
          {"decided", withinNoise.empty() || !failures.empty()}};
}

}  // namespace tl::session
