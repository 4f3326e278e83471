// The editor script's commands (editor/script.h lists them) as a table: each is one small
// function, grouped in files by concern (script_scene.cpp, script_input.cpp, script_viewer.cpp,
// script_albedo.cpp, script_compare.cpp, script_settings.cpp, script_frames.cpp,
// script_lights.cpp, script_work.cpp). A command does its action, or checks its expectation and throws
// ScriptFailure with what it found; it may leave a wait (ScriptState) that holds the lines
// after it until the editor has done what it started (script_waits.cpp).
// A new command: a function in the file of its concern and a line in that file's table.
#pragma once

#include "frame_profile.h"

#include <glm/glm.hpp>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tl::editor {

class EditorApp;

// A failed action or expectation: the script stops with this message and its line number.
struct ScriptFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What the lines of a script share: the waits a command leaves for the lines after it, and what
// an expectation compares with (the snapshot, the camera at the last copy-file, ...).
struct ScriptState {
  // `wait N`: N engine frames finish (N UI frames while the engine has nothing to render).
  int waitFrames = 0;
  uint64_t waitUntil = 0;  // engine frames begun when the wait ends
  bool waitScreenshot = false, waitCapture = false, waitLoaded = false, waitBake = false;
  bool waitTune = false;  // wait-tune: until the tune job ends, or tuneDeadline
  std::chrono::steady_clock::time_point tuneDeadline;
  std::string waitShaderError;  // expect-shader-error's text
  int shaderErrorFrames = 0;
  int scrollFrames = 0;  // frames click-ui has waited for its control to scroll into view
  bool repeatLine = false;  // run this line again next frame (click-ui waiting for its control)

  // `measure N`: the UI loop's rate over N passes, from these counts at its start.
  struct Measure {
    int framesLeft = 0;
    uint64_t uiStart = 0, engineStart = 0, presentedStart = 0, supersededStart = 0;
    double cpu = 0.0, processCpu = 0.0, seconds = 0.0;
    std::map<std::string, double> threads;  // frame_profile.h, at the start
    FrameProfile profile;
  } measure;

  // snapshot / expect-viewport-changed: the viewport read back on the next frame.
  enum class Capture { None, Snapshot, Compare } capture = Capture::None;
  int captureWaitFrames = 0;
  double changedAtLeast = 0.01;  // expect-viewport-changed's least mean difference
  std::vector<float> snapshot;

  uint32_t samplesAtMove = 0, restartsAtMove = 0;  // the live reference when the camera last moved
  // The last copy-file: the reload count and the camera then, for expect-reload.
  uint64_t reloadsAtCopy = 0;
  glm::dvec3 cameraAtCopy{0.0};
  bool reloadWaiting = false;  // expect-reload, since reloadWaitStart
  std::chrono::steady_clock::time_point reloadWaitStart;
};

// A command: `arg` is the rest of its line, leading spaces removed.
using ScriptCommandFn = void (*)(EditorApp& app, ScriptState& state, const std::string& arg);
struct ScriptCommand {
  std::string_view name;
  ScriptCommandFn run;
};

std::span<const ScriptCommand> sceneScriptCommands();
std::span<const ScriptCommand> inputScriptCommands();
std::span<const ScriptCommand> viewerScriptCommands();
std::span<const ScriptCommand> albedoScriptCommands();
std::span<const ScriptCommand> compareScriptCommands();
std::span<const ScriptCommand> settingsScriptCommands();
std::span<const ScriptCommand> frameScriptCommands();
std::span<const ScriptCommand> lightScriptCommands();
std::span<const ScriptCommand> workScriptCommands();

// The command called `name` in any group; nothing for an unknown one.
const ScriptCommand* findScriptCommand(std::string_view name);

// Whether a wait a command left still holds the next line (script_waits.cpp): true while it
// does; ScriptFailure when what it waits for cannot come (a timeout, an unchanged viewport).
bool scriptWaiting(EditorApp& app, ScriptState& state);

// CPU seconds of the calling thread and of the whole process (measure).
double threadCpuSeconds();
double processCpuSeconds();

}  // namespace tl::editor
