#include "bench.h"

#include <fmt/format.h>

#include <algorithm>

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  double pos = q * double(v.size() - 1);
  size_t i = size_t(pos);
  double f = pos - double(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

nlohmann::json stats(const std::vector<double>& ms) {
  return {{"median", quantile(ms, 0.5)}, {"p10", quantile(ms, 0.1)}, {"p90", quantile(ms, 0.9)},
          {"min", quantile(ms, 0.0)},    {"max", quantile(ms, 1.0)}};
}

}  // namespace

nlohmann::json runBench(tl::session::Session& session, const BenchOptions& o) {
  session.renderFrames(std::max(1u, o.warmup));
  std::vector<double> firstFrame = session.frameGpuMs();
  session.renderFrames(std::max(1u, o.frames));
  const auto& d = session.device();
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& [pass, ms] : session.passGpuMs()) {
    auto s = stats(ms);
    s["pass"] = pass;
    passes.push_back(s);
  }
  return {{"scene", session.scene().name},
          {"path", session.path()},
          {"width", session.settings().width},
          {"height", session.settings().height},
          {"frames", o.frames},
          {"warmupFrames", o.warmup},
          {"firstFrameMs", firstFrame.empty() ? 0.0 : firstFrame.front()},
          {"device", d.name()},
          {"driver", d.driver()},
          {"vulkan", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion()), VK_API_VERSION_MINOR(d.apiVersion()),
                                 VK_API_VERSION_PATCH(d.apiVersion()))},
          {"frame", stats(session.frameGpuMs())},
          {"passes", passes}};
}

std::string benchTable(const nlohmann::json& r) {
  std::string s = fmt::format("{} / {} at {}x{} on {} ({} frames after {} warm-up; first frame {:.1f} ms)\n",
                              r["scene"].get<std::string>(), r["path"].get<std::string>(), r["width"].get<int>(),
                              r["height"].get<int>(), r["device"].get<std::string>(), r["frames"].get<int>(),
                              r["warmupFrames"].get<int>(), r["firstFrameMs"].get<double>());
  s += fmt::format("  {:24} {:>9} {:>9} {:>9}\n", "pass", "median ms", "p10", "p90");
  auto row = [&](const std::string& name, const nlohmann::json& st) {
    s += fmt::format("  {:24} {:9.2f} {:9.2f} {:9.2f}\n", name, st["median"].get<double>(), st["p10"].get<double>(),
                     st["p90"].get<double>());
  };
  for (const auto& p : r["passes"]) row(p["pass"].get<std::string>(), p);
  row("frame", r["frame"]);
  return s;
}
