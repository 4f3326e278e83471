// The waits a script command leaves (script_commands.h): each holds the next line until what
// its command started is done, checked in this order every frame.
#include "script_commands.h"

#include "editor_app.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <thread>

namespace tl::editor {
namespace {

double cpuSeconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// `measure N`: the UI loop's rate, the presented frames and the engine's rate over the N passes.
void printMeasurement(EditorApp& app, const ScriptState::Measure& m) {
  const double seconds = wallSeconds() - m.seconds;
  const uint64_t frames = app.uiFrames() - m.uiStart, engine = app.engineFramesDone() - m.engineStart;
  const uint64_t presented = app.framesPresented() - m.presentedStart;
  const uint64_t superseded = app.framesSuperseded() - m.supersededStart;
  const double cpu = threadCpuSeconds() - m.cpu, processCpu = processCpuSeconds() - m.processCpu;
  const auto& compare = app.compareView();
  const std::string path = compare ? fmt::format("compare {} | {}", compare->left, compare->right) : app.session().path();
  // The UI's frame rate is its loop's: every pass takes the input and runs the panels.
  // Presented frames are the passes that drew the window (what changed on screen).
  fmt::print("editor: UI loop {:.1f} fps over {} passes, window presented {:.1f} fps ({} frames; {} replaced "
             "by a newer one before drawn), engine {:.2f} fps ({} frames), frame on screen {:.0f} ms old, "
             "UI thread {:.1f} ms CPU a pass, process {:.0f}% of a core, render {}x{}, path {}, {}\n",
             double(frames) / seconds, frames, double(presented) / seconds, presented, superseded,
             double(engine) / seconds, engine, 1000.0 * app.shownFrameAge(),
             1000.0 * cpu / double(std::max<uint64_t>(frames, 1)), 100.0 * processCpu / seconds,
             app.session().settings().width, app.session().settings().height, path, app.session().device().name());
  // Where the frames went: the UI thread's wall time by phase, then CPU by thread group
  // (the engine's threads run at a lower priority and are marked so), per UI frame.
  const FrameProfile& p = app.frameProfile();
  const double perFrame = 1000.0 / double(std::max<uint64_t>(frames, 1));
  fmt::print("editor: a UI pass's wall time: input {:.1f} ms, panels {:.1f} ms, present {:.1f} ms, pacing sleep {:.1f} ms\n",
             perFrame * (p.input - m.profile.input), perFrame * (p.panels - m.profile.panels),
             perFrame * (p.present - m.profile.present), perFrame * (p.sleep - m.profile.sleep));
  std::vector<std::pair<double, std::string>> threads;
  for (const auto& [group, cpuNow] : threadCpuByGroup()) {
    auto before = m.threads.find(group);
    const double used = cpuNow - (before == m.threads.end() ? 0.0 : before->second);
    if (used > 0.0) threads.push_back({used, group});
  }
  std::sort(threads.rbegin(), threads.rend());
  std::string list;
  for (const auto& [used, group] : threads) list += fmt::format("{}{} {:.1f}", list.empty() ? "" : ", ", group, perFrame * used);
  double load[3] = {};
  std::ifstream("/proc/loadavg") >> load[0] >> load[1] >> load[2];
  fmt::print("editor: CPU ms a UI pass by thread: {}; machine load {:.1f} on {} CPUs\n", list, load[0],
             std::thread::hardware_concurrency());
}

// Each wait: true while it holds the next line.
bool measuring(EditorApp& app, ScriptState& s) {
  if (s.measure.framesLeft <= 0) return false;
  if (--s.measure.framesLeft == 0) printMeasurement(app, s.measure);
  return true;
}

bool waitingForFrames(EditorApp& app, ScriptState& s) {
  if (s.waitFrames <= 0) return false;
  if (app.engineActive() ? app.engineFramesDone() < s.waitUntil : --s.waitFrames > 0) return true;
  s.waitFrames = 0;
  return false;
}

bool waitingForScreenshot(EditorApp& app, ScriptState& s) {
  if (!s.waitScreenshot) return false;
  if (app.screenshotPending()) return true;
  s.waitScreenshot = false;
  return false;
}

bool waitingForCapture(EditorApp& app, ScriptState& s) {
  if (!s.waitCapture) return false;
  if (app.frameCapturePending()) return true;
  s.waitCapture = false;
  return false;
}

bool waitingForLoad(EditorApp& app, ScriptState& s) {
  if (!s.waitLoaded) return false;
  if (app.loading()) return true;
  s.waitLoaded = false;
  return false;
}

bool waitingForShaderError(EditorApp& app, ScriptState& s) {
  if (s.waitShaderError.empty()) return false;
  std::vector<std::string> errors = app.shaderReloader() ? app.shaderReloader()->errors() : std::vector<std::string>{};
  auto hit = std::find_if(errors.begin(), errors.end(), [&](auto& e) { return e.find(s.waitShaderError) != std::string::npos; });
  if (hit == errors.end()) {
    if (++s.shaderErrorFrames > 120) throw ScriptFailure(fmt::format("no shader error containing `{}`", s.waitShaderError));
    return true;
  }
  fmt::print("script: shader error reported: {}\n", *hit);
  s.waitShaderError.clear();
  return false;
}

bool waitingForReload(EditorApp& app, ScriptState& s) {
  if (!s.reloadWaiting) return false;
  if (app.sceneReloads() == s.reloadsAtCopy || app.loading()) {
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - s.reloadWaitStart).count();
    if (waited > 60.0) throw ScriptFailure("the scene was not reloaded within 60 s of its file changing");
    return true;
  }
  s.reloadWaiting = false;
  const glm::dvec3 now = app.cameraView().position;
  if (glm::length(now - s.cameraAtCopy) > 1e-6)
    throw ScriptFailure(fmt::format("the reload moved the camera from {:.3f},{:.3f},{:.3f} to {:.3f},{:.3f},{:.3f}",
                                    s.cameraAtCopy.x, s.cameraAtCopy.y, s.cameraAtCopy.z, now.x, now.y, now.z));
  fmt::print("script: the scene reloaded; the camera stayed at {:.3f},{:.3f},{:.3f}\n", now.x, now.y, now.z);
  return false;
}

bool waitingForBake(EditorApp& app, ScriptState& s) {
  if (!s.waitBake) return false;
  if (app.albedoBake()) return true;
  s.waitBake = false;
  fmt::print("script: albedo bake {}\n", app.lastBakeSummary());
  return false;
}

bool waitingForTune(EditorApp& app, ScriptState& s) {
  if (!s.waitTune) return false;
  if (app.tuneJob()) {
    if (std::chrono::steady_clock::now() > s.tuneDeadline) throw ScriptFailure("the tune did not finish in time");
    return true;
  }
  s.waitTune = false;
  fmt::print("script: tune {}\n", app.lastTuneSummary());
  return false;
}

// snapshot / expect-viewport-changed: the viewport read back by the engine's next frame.
bool waitingForViewport(EditorApp& app, ScriptState& s) {
  if (s.capture == ScriptState::Capture::None) return false;
  if (app.viewportCapture().empty()) {
    // The engine's next frame brings it (a slow path takes a while).
    if (++s.captureWaitFrames > 6000) throw ScriptFailure("the viewport could not be read back");
    return true;
  }
  if (s.capture == ScriptState::Capture::Snapshot) {
    s.snapshot = app.viewportCapture();
  } else {
    const auto& now = app.viewportCapture();
    if (now.size() != s.snapshot.size()) throw ScriptFailure("the viewport changed size since the snapshot");
    double diff = 0.0;
    for (size_t i = 0; i < now.size(); ++i) diff += std::abs(now[i] - s.snapshot[i]);
    diff /= double(now.size());
    if (diff < s.changedAtLeast)
      throw ScriptFailure(fmt::format("the viewport did not change (mean difference {:.4f}, at least {:g} expected)", diff,
                                      s.changedAtLeast));
    fmt::print("script: the viewport changed (mean difference {:.3f})\n", diff);
  }
  s.capture = ScriptState::Capture::None;
  return false;
}

}  // namespace

double threadCpuSeconds() { return cpuSeconds(CLOCK_THREAD_CPUTIME_ID); }
double processCpuSeconds() { return cpuSeconds(CLOCK_PROCESS_CPUTIME_ID); }

bool scriptWaiting(EditorApp& app, ScriptState& state) {
  for (auto waiting : {measuring, waitingForFrames, waitingForScreenshot, waitingForCapture, waitingForLoad,
                       waitingForShaderError, waitingForReload, waitingForBake, waitingForTune, waitingForViewport})
    if (waiting(app, state)) return true;
  return false;
}

}  // namespace tl::editor
