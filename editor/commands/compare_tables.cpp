#include "compare_tables.h"

#include "session/sweep_summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tl::editor {
namespace {

// A report's figure in a column `width` wide with `decimals`, or "-" where the report holds none:
// a figure that is undefined for the view (the PSNR of two equal images, a mean ratio against a
// black reference) is stored as null, and a table shows no "nan".
std::string cell(const nlohmann::json& v, int width, int decimals) {
  if (!v.is_number()) return fmt::format("{:>{}}", "-", width);
  return fmt::format("{:{}.{}f}", v.get<double>(), width, decimals);
}

// " (95% interval LOW .. HIGH)" for a figure whose interval has a width, else nothing.
std::string interval(const nlohmann::json& f) {
  if (!f.contains("low") || !f["low"].is_number() || !f["high"].is_number()) return "";
  const double low = f["low"].get<double>(), high = f["high"].get<double>();
  return high > low ? fmt::format(" (95% interval {:.4f} .. {:.4f})", low, high) : "";
}

// A noise-aware figure as "VALUE [LOW, HIGH]" in a column `width` wide.
std::string figureCell(const nlohmann::json& f, int width) {
  if (!f.is_object() || !f["value"].is_number()) return fmt::format("{:>{}}", "-", width);
  if (!f["low"].is_number() || !f["high"].is_number()) return fmt::format("{:>{}.4f}", f["value"].get<double>(), width);
  return fmt::format("{:>{}}", fmt::format("{:.4f} [{:.4f}, {:.4f}]", f["value"].get<double>(), f["low"].get<double>(),
                                           f["high"].get<double>()), width);
}

// The figures against the converged reference and the rankings they support.
void printSignificance(const nlohmann::json& report) {
  if (!report.contains("significance")) return;
  const auto& sig = report["significance"];
  fmt::print("against the converged reference (its noise taken out; 95% interval from the reference's noise)\n");
  fmt::print("{:10} {:>26} {:>26} {:>26} {:>26}\n", "path", "relMSE", "relMSE_norm", "FLIP", "FLIP_norm");
  for (auto& p : report["paths"]) {
    if (!p.contains("significance")) continue;
    const auto& f = p["significance"];
    fmt::print("{:10} {} {} {} {}\n", p["path"].get<std::string>(), figureCell(f["relMSE"], 26),
               figureCell(f["relMSE_norm"], 26), figureCell(f["FLIP"], 26), figureCell(f["FLIP_norm"], 26));
  }
  if (sig.contains("rankings") && report["paths"].size() > 1) {
    std::string line;
    for (auto& metric : sig["metrics"])
      if (sig["rankings"].contains(metric.get<std::string>()))
        line += fmt::format("{}{}: {}", line.empty() ? "" : "; ", metric.get<std::string>(),
                            sig["rankings"][metric.get<std::string>()]["order"].get<std::string>());
    fmt::print("ranking (< lower, ~ within noise): {}\n", line);
  }
}

}  // namespace

void printCompareReport(const nlohmann::json& report, const std::vector<session::GateThreshold>& failAbove) {
  fmt::print("as rendered (linear radiance; SSIM and FLIP of the display images at {:.2f} EV)\n",
             report["exposureEV"].get<double>());
  fmt::print("{:10} {:>9} {:>9} {:>9} {:>8} {:>7} {:>7} {:>9}\n", "path", "GPU ms", "relMSE", "RMSE", "PSNR", "SSIM", "FLIP",
             "HDR-FLIP");
  for (auto& p : report["paths"])
    fmt::print("{:10} {:9.2f} {} {} {} {} {} {}\n", p["path"].get<std::string>(), p["frameMs"].get<double>(),
               cell(p["relMSE"], 9, 4), cell(p["RMSE"], 9, 4), cell(p["PSNR"], 8, 2), cell(p["SSIM"], 7, 4),
               cell(p["FLIP"], 7, 4), cell(p["HDR-FLIP"], 9, 4));
  fmt::print("exposure-normalised (both images x{:.4g}: the reference's mean Y {:.4g} -> 0.18)\n",
             report["reference"]["normalisation"].get<double>(), report["reference"]["meanLuminance"].get<double>());
  fmt::print("{:10} {:>11} {:>11} {:>11} {:>10}\n", "path", "relMSE_norm", "RMSE_norm", "FLIP_norm", "mean ratio");
  for (auto& p : report["paths"])
    fmt::print("{:10} {} {} {} {}\n", p["path"].get<std::string>(), cell(p["relMSE_norm"], 11, 4), cell(p["RMSE_norm"], 11, 4),
               cell(p["FLIP_norm"], 11, 4), cell(p.value("meanRatio", nlohmann::json()), 10, 3));
  printSignificance(report);
  fmt::print("per stage (surface pixels)  {:>13} {:>18}\n", "AO abs error", "irradiance relMSE");
  for (auto& p : report["paths"])
    if (p["stages"].contains("ao"))
      fmt::print("{:27} {} {}\n", p["path"].get<std::string>(), cell(p["stages"]["ao"]["meanAbsError"], 13, 4),
                 cell(p["stages"]["irradiance"]["relMSE"], 18, 4));
  const auto& ref = report["reference"];
  if (ref["source"] == "file") {
    fmt::print("reference: {} (external)\n", ref["file"].get<std::string>());
  } else {
    fmt::print("reference: {} spp{}{}\n", ref["spp"].get<int>(), ref["scope"] == "same" ? ", same scope (direct + one bounce)" : "",
               ref["cached"].get<bool>() ? " (reused from the cache)" : "");
    fmt::print("reference bounces: {}\n", ref["bouncePolicy"].get<std::string>());
    if (ref.contains("noise") && ref["noise"].contains("relativeStdError")) {
      std::string target;
      if (ref.contains("noiseTarget"))
        target = fmt::format(" (target {}: {})", ref["noiseTarget"]["relativeStdError"].get<double>(),
                             ref["noise"].value("reached", false) ? "reached" : "not reached, the sample cap stopped it");
      std::string expected;
      if (ref["noise"].contains("expectedRelMSE_norm"))
        expected = fmt::format("; expected relMSE_norm against the converged image {:.5f}",
                               ref["noise"]["expectedRelMSE_norm"].get<double>());
      fmt::print("reference noise: relative standard error {:.5f}{}{}\n", ref["noise"]["relativeStdError"].get<double>(),
                 target, expected);
    }
  }
  fmt::print("materials: {}\n", ref["materials"].get<std::string>());
  // Per bounce: which share of each depth group of the reference each path holds.
  bool anyBounces = false;
  for (auto& p : report["paths"]) anyBounces |= p.contains("bounces") && p["bounces"].contains("groups");
  anyBounces = anyBounces && report["reference"].contains("byDepth");
  if (anyBounces) {
    const auto share = [](const nlohmann::json& v) { return v.is_number() ? fmt::format("{:.1f}%", 100.0 * v.get<double>()) : std::string("-"); };
    std::string header = fmt::format("{:10}", "captured");
    for (auto& g : report["reference"]["byDepth"]["groups"])
      header += fmt::format(" {:>17}", fmt::format("{} ({})", g["group"].get<std::string>(), share(g["shareOfReference"])));
    fmt::print("per bounce (share of each depth group's light a path holds; the group's share of the reference)\n{} {:>8}\n",
               header, "excess");
    for (auto& p : report["paths"]) {
      if (!p.contains("bounces") || !p["bounces"].contains("groups")) continue;
      std::string row = fmt::format("{:10}", p["path"].get<std::string>());
      for (auto& g : p["bounces"]["groups"]) row += fmt::format(" {:>17}", share(g["captured"]));
      fmt::print("{} {:>8}\n", row, share(p["bounces"]["excess"]));
    }
    fmt::print("missing light per bounce (a fraction of the reference's light)\n");
    for (auto& p : report["paths"]) {
      if (!p.contains("bounces") || !p["bounces"].contains("groups")) continue;
      std::string row = fmt::format("{:10}", p["path"].get<std::string>());
      for (auto& g : p["bounces"]["groups"]) row += fmt::format(" {:>17}", share(g["missing"]));
      fmt::print("{}\n", row);
    }
    for (auto& p : report["paths"])
      if (p.contains("bounces") && p["bounces"].contains("summary"))
        fmt::print("{}: {}\n", p["path"].get<std::string>(), p["bounces"]["summary"].get<std::string>());
  }
  // Per lobe: the light the surfaces reflect through their diffuse layer and their specular lobes.
  if (report["reference"].contains("byLobe")) {
    const auto share = [](const nlohmann::json& v) {
      return v.is_number() ? fmt::format("{:.1f}%", 100.0 * v.get<double>()) : std::string("-");
    };
    const auto& lobes = report["reference"]["byLobe"];
    fmt::print(
        "per lobe (share of the light reflected through each lobe a path holds; the lobe's share of the reference)\n");
    size_t width = 10;  // the longest name (a configuration's may be long)
    for (auto& p : report["paths"]) width = std::max(width, p["path"].get<std::string>().size());
    fmt::print("{:{}} {:>17} {:>17} {:>20} {:>21}\n", "captured", width,
               fmt::format("diffuse ({})", share(lobes["diffuseShare"])),
               fmt::format("specular ({})", share(lobes["specularShare"])), "diffuse relMSE_norm",
               "specular relMSE_norm");
    for (auto& p : report["paths"]) {
      if (!p.contains("lobes") || !p["lobes"].contains("specular")) continue;
      const auto& l = p["lobes"];
      fmt::print("{:{}} {:>17} {:>17} {} {}\n", p["path"].get<std::string>(), width, share(l["diffuse"]["captured"]),
                 share(l["specular"]["captured"]), cell(l["diffuse"]["relMSE_norm"], 20, 4),
                 cell(l["specular"]["relMSE_norm"], 21, 4));
    }
    for (auto& p : report["paths"])
      if (p.contains("lobes") && p["lobes"].contains("summary"))
        fmt::print("{}: {}\n", p["path"].get<std::string>(), p["lobes"]["summary"].get<std::string>());
  }
  if (report.contains("gate")) {
    const auto& gate = report["gate"];
    for (auto& f : gate["failures"])
      fmt::print("gate: FAIL {} {} {} > {}{}\n", f["path"].get<std::string>(), f["metric"].get<std::string>(),
                 f["value"].is_number() ? fmt::format("{:.4f}", f["value"].get<double>()) : std::string("non-finite"),
                 f["threshold"].get<double>(), interval(f));
    if (gate.contains("withinNoise"))
      for (auto& f : gate["withinNoise"])
        fmt::print("gate: within noise {} {} {:.4f}{} holds {}: the reference's noise cannot tell (a reference with "
                   "more samples, --spp or --reference-noise, decides it)\n",
                   f["path"].get<std::string>(), f["metric"].get<std::string>(), f["value"].get<double>(), interval(f),
                   f["threshold"].get<double>());
    std::string limits;
    if (!failAbove.empty())
      for (const auto& t : failAbove) limits += fmt::format("{}{} <= {}", limits.empty() ? "" : ", ", t.metric, t.value);
    else
      for (auto& [metric, value] : gate["failAbove"].items())
        limits += fmt::format("{}{} <= {}", limits.empty() ? "" : ", ", metric, value.get<double>());
    fmt::print("gate: {} ({})\n",
               gate["passed"].get<bool>()        ? "passed"
               : gate.value("decided", true)     ? "FAILED"
                                                 : "UNDECIDED, within the reference's noise",
               limits);
  }
}

void printSweepReport(const nlohmann::json& report) {
  fmt::print("== sweep: {} view(s); each configuration's mean over them\n", report["views"].size());
  fmt::print("{:20} {:>9} {:>9} {:>7} {:>11} {:>11}\n", "configuration", "GPU ms", "relMSE", "FLIP", "relMSE_norm", "FLIP_norm");
  for (auto& c : report["configurations"])
    fmt::print("{:20} {} {} {} {} {}\n", c["path"].get<std::string>(), cell(c["frameMs"], 9, 2), cell(c["relMSE"], 9, 4),
               cell(c["FLIP"], 7, 4), cell(c["relMSE_norm"], 11, 4), cell(c["FLIP_norm"], 11, 4));
  if (report.contains("gate"))
    for (auto& f : report["gate"]["failures"])
      fmt::print("gate: FAIL {} {} {} {} {} > {}\n", f["scene"].get<std::string>(), f["camera"].get<std::string>(),
                 f["path"].get<std::string>(), f["metric"].get<std::string>(),
                 f["value"].is_number() ? fmt::format("{:.4f}", f["value"].get<double>()) : std::string("non-finite"),
                 f["threshold"].get<double>());
  // Per view and path, and the share of views that meet each accuracy goal.
  if (report.contains("summary")) fmt::print("\n{}", tl::session::sweepSummaryTable(report["summary"]));
}

int gateExit(size_t failures, size_t withinNoise) {
  if (failures == 0 && withinNoise == 0) return 0;
  std::fflush(stdout);  // the figures first, then the error line
  if (failures > 0) {
    fmt::print(stderr, "twinlight: error: regression gate failed: {} figure(s) above their thresholds\n", failures);
    return 3;
  }
  fmt::print(stderr,
             "twinlight: error: regression gate undecided: {} figure(s) within the reference's noise of their thresholds "
             "(render the reference with more samples: --spp or --reference-noise)\n",
             withinNoise);
  return 5;
}

}  // namespace tl::editor
