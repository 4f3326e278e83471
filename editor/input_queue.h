// Input between frames: every key, button, character, wheel step and cursor move the window
// receives (GLFW callbacks) and every one a script injects goes into one queue, and each UI
// frame hands Dear ImGui what happened since the last one. A key or button that goes down
// and up again within one frame is not lost: the second change of the same key or button
// waits for the next frame (so a quick tap is seen pressed, then released, and a double
// click is two clicks), and a button change is seen at the cursor position it happened at.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <deque>
#include <string>

struct GLFWwindow;
struct ImGuiIO;

namespace tl::editor {

struct InputEvent {
  // Frame: what follows waits for the next frame (a script's drag moves across frames).
  enum class Kind { Move, Button, Key, Char, Wheel, Frame } kind = Kind::Move;
  glm::vec2 position{0.0f};  // Move
  int code = 0;              // Button (0 left, 1 right, 2 middle), Key (GLFW key), Char (code point)
  bool down = false;         // Button, Key
  glm::vec2 wheel{0.0f};     // Wheel (x, y steps)
};

class InputQueue {
 public:
  // Routes the window's input here (Dear ImGui's backend then installs no callbacks).
  void attach(GLFWwindow* window);
  void push(const InputEvent& e) { events_.push_back(e); }
  // A person's click at `position` (window pixels): move, press, release.
  void click(glm::vec2 position);
  // Sets this frame's mouse position, buttons, keys, modifiers, characters and wheel in `io`
  // (after the backend's NewFrame, before ImGui::NewFrame).
  void feed(ImGuiIO& io);
  bool pending() const { return !events_.empty(); }
  glm::vec2 mousePosition() const { return mouse_; }

 private:
  std::deque<InputEvent> events_;
  glm::vec2 mouse_{-1e6f, -1e6f};
  std::array<bool, 5> buttons_{};
  std::array<bool, 512> keys_{};
};

}  // namespace tl::editor
