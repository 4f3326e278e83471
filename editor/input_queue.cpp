#include "input_queue.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <set>

namespace tl::editor {
namespace {

InputQueue& queueOf(GLFWwindow* window) { return *static_cast<InputQueue*>(glfwGetWindowUserPointer(window)); }

}  // namespace

void InputQueue::attach(GLFWwindow* window) {
  // The window's user pointer is the queue: EditorApp keeps its own state elsewhere.
  glfwSetWindowUserPointer(window, this);
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    queueOf(w).push({InputEvent::Kind::Move, glm::vec2(float(x), float(y))});
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    queueOf(w).push({InputEvent::Kind::Move, glm::vec2(float(x), float(y))});
    queueOf(w).push({InputEvent::Kind::Button, {}, button, action == GLFW_PRESS});
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_REPEAT) return;  // Dear ImGui derives repeats from the held key
    queueOf(w).push({InputEvent::Kind::Key, {}, key, action == GLFW_PRESS});
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned int c) { queueOf(w).push({InputEvent::Kind::Char, {}, int(c)}); });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double x, double y) {
    queueOf(w).push({InputEvent::Kind::Wheel, {}, 0, false, glm::vec2(float(x), float(y))});
  });
}

void InputQueue::click(glm::vec2 position) {
  // The pointer arrives a frame before it presses, as a person's does: Dear ImGui lets an item
  // that may overlap others (a tab) take a press only when it was hovered the frame before.
  push({InputEvent::Kind::Move, position});
  push({InputEvent::Kind::Frame});
  push({InputEvent::Kind::Button, {}, 0, true});
  push({InputEvent::Kind::Button, {}, 0, false});
}

void InputQueue::feed(ImGuiIO& io) {
  std::set<int> changedButtons, changedKeys;
  bool buttonChanged = false;
  while (!events_.empty()) {
    const InputEvent& e = events_.front();
    if (e.kind == InputEvent::Kind::Frame) {
      events_.pop_front();
      break;
    }
    if (e.kind == InputEvent::Kind::Button) {
      if (e.code < 0 || e.code >= int(buttons_.size())) {
        events_.pop_front();
        continue;
      }
      if (changedButtons.count(e.code)) break;  // its second change: next frame
      changedButtons.insert(e.code);
      buttons_[size_t(e.code)] = e.down;
      buttonChanged = true;
    } else if (e.kind == InputEvent::Kind::Key) {
      if (e.code >= 0 && e.code < int(keys_.size())) {
        if (changedKeys.count(e.code)) break;
        changedKeys.insert(e.code);
        keys_[size_t(e.code)] = e.down;
      }
    } else if (e.kind == InputEvent::Kind::Move) {
      // A button change is seen where it happened: a move after it waits for the next frame.
      if (buttonChanged) break;
      mouse_ = e.position;
    } else if (e.kind == InputEvent::Kind::Char) {
      if (e.code > 0 && e.code < 0x110000) io.AddInputCharacter(unsigned(e.code));
    } else {
      io.MouseWheelH += e.wheel.x;
      io.MouseWheel += e.wheel.y;
    }
    events_.pop_front();
  }
  io.MousePos = ImVec2(mouse_.x, mouse_.y);
  for (size_t i = 0; i < buttons_.size(); ++i) io.MouseDown[i] = buttons_[i];
  for (size_t k = 0; k < keys_.size() && k < IM_ARRAYSIZE(io.KeysDown); ++k) io.KeysDown[k] = keys_[k];
  io.KeyCtrl = keys_[GLFW_KEY_LEFT_CONTROL] || keys_[GLFW_KEY_RIGHT_CONTROL];
  io.KeyShift = keys_[GLFW_KEY_LEFT_SHIFT] || keys_[GLFW_KEY_RIGHT_SHIFT];
  io.KeyAlt = keys_[GLFW_KEY_LEFT_ALT] || keys_[GLFW_KEY_RIGHT_ALT];
  io.KeySuper = keys_[GLFW_KEY_LEFT_SUPER] || keys_[GLFW_KEY_RIGHT_SUPER];
}

}  // namespace tl::editor
