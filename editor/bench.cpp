#include "bench.h"

#include "session/provenance.h"
#include "session/ray_figures.h"
#include "session/settings_json.h"
#include "metrics/statistics.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

namespace {

using tl::metrics::quantile;

nlohmann::json stats(const std::vector<double>& ms) {
  return {{"median", quantile(ms, 0.5)}, {"p10", quantile(ms, 0.1)}, {"p90", quantile(ms, 0.9)},
          {"min", quantile(ms, 0.0)},    {"max", quantile(ms, 1.0)}};
}


// Wall-clock milliseconds per frame over `frames` frames, the host's recording included.
double wallMsPerFrame(tl::session::Session& session, uint32_t frames) {
  const auto start = std::chrono::steady_clock::now();
  session.renderFrames(frames);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / double(frames);
}

// One frame in flight against `inFlight`, in alternating turns (a drift of the machine's
// load between the two falls on both): the mean of each side's turns and their ratio.
nlohmann::json inFlightComparison(tl::session::Session& session, uint32_t inFlight, uint32_t frames) {
  constexpr int kTurns = 2;
  double one = 0.0, many = 0.0;
  for (int turn = 0; turn < kTurns; ++turn) {
    session.setFramesInFlight(1);
    one += wallMsPerFrame(session, frames) / kTurns;
    session.setFramesInFlight(inFlight);
    many += wallMsPerFrame(session, frames) / kTurns;
  }
  return {{"framesInFlight", inFlight},
          {"oneInFlightWallMs", one},
          {"framesInFlightWallMs", many},
          {"speedup", many > 0.0 ? one / many : 0.0},
          {"turns", kTurns}};
}

}  // namespace

nlohmann::json runBench(tl::session::Session& session, const BenchOptions& o,
                        const std::function<void(const std::string& what, double fraction)>& progress) {
  const uint32_t warmup = std::max(1u, o.warmup), measured = std::max(1u, o.frames);
  auto report = [&](uint32_t done) {
    if (progress)
      progress(done <= warmup ? fmt::format("warm-up {}/{}", done, warmup)
                              : fmt::format("frame {}/{}", done - warmup, measured),
               double(done) / double(warmup + measured));
  };
  if (o.rays) tl::session::enableRayProbe(session);
  session.setFramesInFlight(o.framesInFlight);
  session.renderFrames(warmup, report);
  std::vector<double> firstFrame = session.frameGpuMs();
  // The ray figures read the last frame's pre-trace records and depth: requested before each
  // call (a read-back lasts one renderFrames).
  auto requestRayBuffers = [&] {
    if (o.rays) tl::session::requestRayFigureBuffers(session);
  };
  std::vector<double> frameMs;
  double wallMs = 0.0;  // wall-clock per measured frame
  tl::session::PassTimes passMs;
  auto collect = [&] {
    frameMs.insert(frameMs.end(), session.frameGpuMs().begin(), session.frameGpuMs().end());
    for (const auto& [pass, ms] : session.passGpuMs()) {
      auto it = std::find_if(passMs.begin(), passMs.end(), [&](const auto& p) { return p.first == pass; });
      if (it == passMs.end()) it = passMs.insert(passMs.end(), {pass, {}});
      it->second.insert(it->second.end(), ms.begin(), ms.end());
    }
  };
  if (o.cutEveryFrame) {
    // The history is forgotten before each frame, as on a camera cut: what history rejection
    // costs at worst (the disocclusion rays trace every cell).
    for (uint32_t i = 0; i < measured; ++i) {
      session.resetHistory();
      requestRayBuffers();
      wallMs += wallMsPerFrame(session, 1) / double(measured);
      collect();
      report(warmup + i + 1);
    }
  } else {
    requestRayBuffers();
    const auto start = std::chrono::steady_clock::now();
    session.renderFrames(measured, [&](uint32_t done) { report(warmup + done); });
    wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / double(measured);
    collect();
  }
  const nlohmann::json comparison =
      o.againstOneInFlight ? inFlightComparison(session, o.framesInFlight, measured) : nlohmann::json();
  const auto& d = session.device();
  nlohmann::json figures = nlohmann::json::object();
  for (const auto& [name, value] : session.pathFigures()) figures[name] = value;
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& [pass, ms] : passMs) {
    auto s = stats(ms);
    s["pass"] = pass;
    passes.push_back(s);
  }
  return {{"twinlight", tl::session::twinlightJson()},
          {"scene", session.scene().name},
          {"path", session.path()},
          {"width", session.settings().width},
          {"height", session.settings().height},
          {"frames", o.frames},
          {"warmupFrames", o.warmup},
          {"cutEveryFrame", o.cutEveryFrame},
          {"firstFrameMs", firstFrame.empty() ? 0.0 : firstFrame.front()},
          {"device", d.name()},
          {"driver", d.driver()},
          {"vulkan", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion()), VK_API_VERSION_MINOR(d.apiVersion()),
                                 VK_API_VERSION_PATCH(d.apiVersion()))},
          {"frame", stats(frameMs)},
          {"framesInFlight", o.framesInFlight},
          {"wallMsPerFrame", wallMs},
          {"inFlight", comparison},
          {"passes", passes},
          {"rays", o.rays ? tl::session::rayFigures(session, passMs) : nlohmann::json()},
          {"settings", tl::session::settingsJson(session.settings())},
          {"figures", figures}};
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
  if (r.contains("wallMsPerFrame"))
    s += fmt::format("  wall clock {:.2f} ms per frame with {} frame(s) in flight\n", r["wallMsPerFrame"].get<double>(),
                     r["framesInFlight"].get<int>());
  if (r.contains("inFlight") && r["inFlight"].is_object()) {
    const auto& f = r["inFlight"];
    s += fmt::format("  in flight: {:.2f} ms per frame with 1, {:.2f} with {}: {:.2f}x\n", f["oneInFlightWallMs"].get<double>(),
                     f["framesInFlightWallMs"].get<double>(), f["framesInFlight"].get<int>(), f["speedup"].get<double>());
  }
  if (r.contains("figures") && !r["figures"].empty()) {
    s += "  figures:";
    for (const auto& [name, value] : r["figures"].items()) s += fmt::format(" {}={:g}", name, value.get<double>());
    s += "\n";
  }
  if (r.contains("rays") && r["rays"].is_object() && r["rays"].contains("pathsPerSecond")) {
    const auto& y = r["rays"];
    s += fmt::format("  reference.trace {:.3f} M paths/s; raw kernel {:.2f} M rays/s ({:.2f} rays a path): a path costs {:.1f} raw rays\n",
                     y["pathsPerSecond"].get<double>() * 1e-6, y["rawRaysPerSecond"].get<double>() * 1e-6,
                     y["rawRaysPerPath"].get<double>(), y["rawRaysPerPathTime"].get<double>());
  } else if (r.contains("rays") && r["rays"].is_object()) {
    const auto& y = r["rays"];
    s += fmt::format("  rays: {} real of {} surface pixels (pre-trace answered {:.1f}%), {:.3f} real rays/pixel\n",
                     y["realRays"].get<size_t>(), y["surfacePixels"].get<size_t>(), 100.0 * y["pretraceShare"].get<double>(),
                     y["realRaysPerPixel"].get<double>());
    s += fmt::format("  raw kernel {:.2f} M rays/s, rt.trace {:.2f} M rays/s: {:.0f}% of raw\n",
                     y["rawRaysPerSecond"].get<double>() * 1e-6, y["rtRaysPerSecond"].get<double>() * 1e-6,
                     100.0 * y["rtOverRaw"].get<double>());
    s += fmt::format("  raw kernel on the same (pending) rays {:.2f} M rays/s: rt.trace at {:.0f}% of it\n",
                     y["rawPendingRaysPerSecond"].get<double>() * 1e-6, 100.0 * y["rtOverRawSameRays"].get<double>());
  }
  return s;
}
