#include "session/sweep_summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace tl::session {
namespace {

// Below this share of the brightest view of its scene a view's reference is dark: the inside
// of a sealed room (whose truth is black, up to the reference's noise).
constexpr double kDarkShare = 0.01;

struct Goal {
  const char* id;
  const char* text;
  double target;  // share of the judged views that must meet it
};
constexpr Goal kGoals[] = {
    {"rt_mean", "rt mean within +-10% of the reference", 0.95},
    {"rt_vs_legacy", "rt relMSE_norm <= 0.5x legacy's", 0.90},
    {"legacy_mean", "legacy mean within +-35% of the reference", 0.90},
    {"dark_stays_dark", "dark views stay dark (< 1% of the lit view) in every path", 1.0},
};

// A member of a const object, or null: a const json's operator[] on a missing key is undefined
// behaviour (a merged or older report may lack a figure).
const nlohmann::json& field(const nlohmann::json& object, const char* key) {
  static const nlohmann::json kNull;
  return object.is_object() && object.contains(key) ? object[key] : kNull;
}

std::optional<double> number(const nlohmann::json& object, const char* key) {
  const nlohmann::json& v = field(object, key);
  if (!v.is_number()) return std::nullopt;
  const double d = v.get<double>();
  return std::isfinite(d) ? std::optional<double>(d) : std::nullopt;
}

const nlohmann::json* pathEntry(const nlohmann::json& view, const std::string& path) {
  const nlohmann::json& paths = field(view, "paths");
  if (!paths.is_array()) return nullptr;
  for (const auto& p : paths)
    if (p.value("path", "") == path) return &p;
  return nullptr;
}

// A path's mean luminance in a view: its own figure, or its ratio times the reference's.
std::optional<double> pathMean(const nlohmann::json& entry, double referenceMean) {
  if (auto m = number(entry, "meanLuminance")) return m;
  if (auto r = number(entry, "meanRatio")) return *r * referenceMean;
  return std::nullopt;
}

}  // namespace

nlohmann::json summarizeSweep(const nlohmann::json& report) {
  const nlohmann::json& views = report.at("views");
  // The brightest reference of each scene: what "dark" is measured against.
  std::map<std::string, double> brightest;
  for (const auto& v : views) {
    const std::string scene = v.value("sceneFile", v.value("scene", std::string()));
    const double mean = number(field(v, "reference"), "meanLuminance").value_or(0.0);
    brightest[scene] = std::max(brightest[scene], mean);
  }
  std::vector<std::string> paths;
  for (const auto& v : views)
    for (const auto& p : field(v, "paths"))
      if (std::find(paths.begin(), paths.end(), p.value("path", "")) == paths.end()) paths.push_back(p.value("path", ""));

  std::map<std::string, std::pair<int, int>> tally;  // goal -> (met, judged)
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& v : views) {
    const std::string scene = v.value("sceneFile", v.value("scene", std::string()));
    const double lit = brightest[scene];
    const double mean = number(field(v, "reference"), "meanLuminance").value_or(0.0);
    nlohmann::json row = {{"dir", v.value("dir", "")}, {"scene", v.value("scene", "")}, {"camera", v.value("camera", "")},
                          {"referenceMean", mean}};
    std::vector<std::string> missed;
    auto judge = [&](const char* goal, bool met) {
      auto& t = tally[goal];
      ++t.second;
      if (met) ++t.first;
      else missed.push_back(goal);
    };
    nlohmann::json figures = nlohmann::json::object();
    for (const std::string& path : paths)
      if (const nlohmann::json* e = pathEntry(v, path)) {
        const std::optional<double> pathLuminance = pathMean(*e, mean);
        figures[path] = {{"meanRatio", field(*e, "meanRatio")}, {"relMSE_norm", field(*e, "relMSE_norm")},
                         {"meanLuminance", pathLuminance ? nlohmann::json(*pathLuminance) : nlohmann::json()}};
      }
    row["paths"] = figures;
    if (!(lit > 0.0)) {
      row["class"] = "unlit";  // nothing to judge: every view of the scene is black
    } else if (mean < kDarkShare * lit) {
      row["class"] = "dark";
      bool dark = true;
      for (const std::string& path : paths)
        if (const nlohmann::json* e = pathEntry(v, path)) {
          const auto m = pathMean(*e, mean);
          dark = dark && m && *m < kDarkShare * lit;
        }
      judge("dark_stays_dark", dark);
    } else {
      row["class"] = "lit";
      const nlohmann::json* rt = pathEntry(v, "rt");
      const nlohmann::json* legacy = pathEntry(v, "legacy");
      if (rt) {
        const auto r = number(*rt, "meanRatio");
        judge("rt_mean", r && std::abs(*r - 1.0) <= 0.10);
      }
      if (rt && legacy) {
        const auto a = number(*rt, "relMSE_norm"), b = number(*legacy, "relMSE_norm");
        judge("rt_vs_legacy", a && b && *a <= 0.5 * *b);
      }
      if (legacy) {
        const auto r = number(*legacy, "meanRatio");
        judge("legacy_mean", r && std::abs(*r - 1.0) <= 0.35);
      }
    }
    row["missed"] = missed;
    rows.push_back(row);
  }
  nlohmann::json goals = nlohmann::json::array();
  for (const Goal& g : kGoals) {
    if (!tally.count(g.id)) continue;
    const auto [met, judged] = tally[g.id];
    const double share = double(met) / double(judged);
    goals.push_back({{"id", g.id}, {"text", g.text}, {"met", met}, {"judged", judged}, {"share", share},
                     {"target", g.target}, {"held", share + 1e-12 >= g.target}});
  }
  return {{"paths", paths}, {"views", rows}, {"goals", goals}};
}

std::string sweepSummaryTable(const nlohmann::json& summary) {
  const auto& paths = summary["paths"];
  size_t width = 4;
  for (const auto& row : summary["views"]) width = std::max(width, row["dir"].get<std::string>().size());
  std::string out = fmt::format("{:<{}} {:>10}", "view", width, "ref mean");
  for (const auto& p : paths) out += fmt::format(" {:>10} {:>12}", p.get<std::string>() + " ratio", "relMSE_norm");
  out += "  missed\n";
  auto figure = [](const nlohmann::json& v, int digits) {
    return v.is_number() ? fmt::format("{:.{}f}", v.get<double>(), digits) : std::string("-");
  };
  for (const auto& row : summary["views"]) {
    out += fmt::format("{:<{}} {:>10}", row["dir"].get<std::string>(), width, fmt::format("{:.4g}", row["referenceMean"].get<double>()));
    for (const auto& p : paths) {
      const std::string name = p.get<std::string>();
      const auto& f = row["paths"].contains(name) ? row["paths"][name] : nlohmann::json::object();
      out += fmt::format(" {:>10} {:>12}", figure(f.value("meanRatio", nlohmann::json()), 3),
                         figure(f.value("relMSE_norm", nlohmann::json()), 4));
    }
    std::string missed;
    for (const auto& m : row["missed"]) missed += (missed.empty() ? "" : ", ") + m.get<std::string>();
    const std::string cls = row["class"];
    out += fmt::format("  {}{}\n", cls == "lit" ? "" : "(" + cls + ") ", missed);
  }
  out += "\ngoal                                                       met   share  target\n";
  for (const auto& g : summary["goals"])
    out += fmt::format("{:<56} {:>3}/{:<3} {:>5.1f}%  {:>4.0f}%  {}\n", g["text"].get<std::string>(), g["met"].get<int>(),
                       g["judged"].get<int>(), 100.0 * g["share"].get<double>(), 100.0 * g["target"].get<double>(),
                       g["held"].get<bool>() ? "held" : "MISSED");
  return out;
}

}  // namespace tl::session
