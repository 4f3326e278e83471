// Script commands on frames and images: let frames pass, measure the loop's rate, screenshots,
// viewport snapshots and their differences, captures, saved images, RenderDoc, quit.
#include "script_commands.h"

#include "editor_app.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

namespace tl::editor {
namespace {

void wait(EditorApp& app, ScriptState& s, const std::string& arg) {
  s.waitFrames = std::max(0, std::stoi(arg));
  // Frames begun from now on: one in flight was begun with what came before this line.
  s.waitUntil = app.engineFramesBegun() + uint64_t(s.waitFrames);
}

void measure(EditorApp& app, ScriptState& s, const std::string& arg) {
  ScriptState::Measure& m = s.measure;
  m.framesLeft = std::max(1, std::stoi(arg));
  m.uiStart = app.uiFrames();
  m.presentedStart = app.framesPresented();
  m.supersededStart = app.framesSuperseded();
  m.engineStart = app.engineFramesDone();
  m.cpu = threadCpuSeconds();
  m.processCpu = processCpuSeconds();
  m.threads = threadCpuByGroup();
  m.profile = app.frameProfile();
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Taken by the window's thread: the script goes on once it is written.
void screenshot(EditorApp& app, ScriptState& s, const std::string& arg) {
  app.requestScreenshot(arg);
  s.waitScreenshot = true;
}

void readViewport(EditorApp& app, ScriptState& s, ScriptState::Capture capture, double changedAtLeast) {
  s.capture = capture;
  s.changedAtLeast = changedAtLeast;
  s.captureWaitFrames = 0;
  app.requestViewportCapture();
}

void snapshot(EditorApp& app, ScriptState& s, const std::string&) { readViewport(app, s, ScriptState::Capture::Snapshot, 0.01); }

// A noisy path changes by its noise alone: its test names a larger difference.
void expectViewportChanged(EditorApp& app, ScriptState& s, const std::string& arg) {
  if (s.snapshot.empty()) throw ScriptFailure("no snapshot to compare with");
  const double least = arg.empty() ? 0.01 : std::atof(arg.c_str());
  if (!(least > 0.0)) throw ScriptFailure("expect-viewport-changed takes a mean difference above 0");
  readViewport(app, s, ScriptState::Capture::Compare, least);
}

// Written after the next engine frame.
void capture(EditorApp& app, ScriptState& s, const std::string& arg) {
  app.requestFrameCapture(arg.empty() ? app.defaultCaptureFolder() : std::filesystem::path(arg));
  s.waitCapture = true;
}

void saveImage(EditorApp& app, ScriptState&, const std::string& arg) { app.saveImage(arg); }
void renderDocCapture(EditorApp& app, ScriptState&, const std::string&) { app.requestRenderDocCapture(); }
void quit(EditorApp& app, ScriptState&, const std::string&) { app.requestQuit(); }

constexpr ScriptCommand kCommands[] = {
    {"wait", wait},
    {"measure", measure},
    {"screenshot", screenshot},
    {"snapshot", snapshot},
    {"expect-viewport-changed", expectViewportChanged},
    {"capture", capture},
    {"save-image", saveImage},
    {"renderdoc-capture", renderDocCapture},
    {"quit", quit},
};

}  // namespace

std::span<const ScriptCommand> frameScriptCommands() { return kCommands; }

}  // namespace tl::editor
