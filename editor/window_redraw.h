// Whether the window needs drawing again. On a software device drawing the 1600x900 window
// (clearing it, scaling the engine image in, rasterizing the panels) costs ~20 ms of CPU,
// more than a 30 fps interface can spend on every pass of its loop while the engine renders
// on the same cores. Most passes change nothing on screen (no input, no new engine image),
// so the loop runs at its own rate, handling input every pass, and the window is drawn only
// when what it would show differs from what it shows: Dear ImGui's draw data (vertices,
// indices, commands, clip rectangles, textures) hashed, a new engine image, the viewport's
// place, the window's size, an expose of the window, a screenshot.
#pragma once

#include <cstdint>
#include <utility>

struct ImDrawData;

namespace tl::editor {

// A 64-bit hash of everything in `data` that decides the pixels it draws.
uint64_t drawDataHash(const ImDrawData& data);

class WindowRedraw {
 public:
  // Notes what this pass of the loop would draw (a hash of it); a change asks for a redraw.
  void observe(uint64_t drawHash);
  // Something outside the hash changed the window's pixels (a new engine image, an expose, a
  // screenshot to take): draw this pass.
  void invalidate() { pending_ = true; }
  // Whether to draw this pass; the request is then taken.
  bool take() { return std::exchange(pending_, false); }

 private:
  uint64_t last_ = 0;
  bool any_ = false;
  bool pending_ = true;
};

}  // namespace tl::editor
