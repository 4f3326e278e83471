// Whether the window needs drawing again. On a software device drawing the 1600x900 window
// (clearing it, scaling the engine image in, rasterizing the panels) costs ~20 ms of CPU,
// more than a 30 fps interface can spend on every pass of its loop while the engine renders
// on the same cores. Most passes change nothing on screen (no input, no new engine image),
// so the loop runs at its own rate, handling input every pass, and the window is drawn only
// when what it would show differs from what it shows: Dear ImGui's draw data (vertices,
// indices, commands, clip rectangles, textures) hashed, a new engine image, the viewport's
// place, an expose of the window, a screenshot.
#pragma once

#include <cstdint>

struct ImDrawData;

namespace tl::editor {

// A 64-bit hash of everything in `data` that decides the pixels it draws.
uint64_t drawDataHash(const ImDrawData& data);

class WindowRedraw {
 public:
  // Notes what this pass of the loop would draw; true when it differs from the last call
  // (the first call: always).
  bool observe(uint64_t drawHash);
  // Something outside the draw data changed the window's pixels (a new engine image, an
  // expose, a resize): draw at the next chance.
  void invalidate() { pending_ = true; }
  // Whether to draw now. `windowBusy`: the window's previous frame is still being drawn;
  // the UI does not wait for it (on lavapipe presenting waits for the drawing), the redraw
  // stays pending for a later pass. `force`: a screenshot, drawn whatever the wait.
  bool shouldDraw(bool windowBusy, bool force);
  void drew() { pending_ = false; }
  uint64_t deferred() const { return deferred_; }  // passes that had to put a redraw off

 private:
  uint64_t last_ = 0;
  bool any_ = false;
  bool pending_ = true;
  uint64_t deferred_ = 0;
};

}  // namespace tl::editor
