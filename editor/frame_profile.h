// Where the editor's UI frames go, for `measure`: the UI thread's wall time by phase, and
// the CPU time of the process's threads grouped by name and priority (Linux /proc) — the
// interface's thread, the window device's lavapipe threads, the engine's (started at a lower
// priority), the rest.
#pragma once

#include <map>
#include <string>

namespace tl::editor {

// The UI frames' wall time, summed since the start (seconds): events, input and the engine's
// finished frame; the panels and the engine's next frame; recording and presenting the
// window; the pacing sleep.
struct FrameProfile {
  double input = 0.0, panels = 0.0, present = 0.0, sleep = 0.0;
};

// Seconds of CPU (user + system) per group, summed over the threads alive now. A group is
// the thread's name without its trailing number ("llvmpipe-1" -> "llvmpipe"), with " (engine)"
// appended for a thread at a lower priority than the process's main thread. Empty where
// /proc cannot be read.
std::map<std::string, double> threadCpuByGroup();

}  // namespace tl::editor
