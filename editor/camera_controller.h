// Editor camera: orbit around a pivot, pan, dolly, fly (WASD + mouse look), focus on a
// box; speeds scale with the scene's size. Produces a session::View.
#pragma once

#include "scene/scene.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

namespace tl::editor {

struct CameraInput {
  glm::vec2 orbitDelta{0.0f};  // pixels dragged with the orbit button
  glm::vec2 panDelta{0.0f};    // pixels dragged with the pan button
  glm::vec2 lookDelta{0.0f};   // pixels moved while flying
  float dolly = 0.0f;          // wheel steps
  glm::vec3 move{0.0f};        // fly: x right, y up, z forward, each -1..1
  bool fast = false;
  float seconds = 0.0f;        // since the last frame
};

class CameraController {
 public:
  void reset(const session::View& view, double sceneSize);
  void update(const CameraInput& in);
  void focus(const scene::Bounds& bounds);
  // Moves the camera by metres along its own right, up and forward axes (the scripts' step).
  void translate(const glm::dvec3& rightUpForward);
  session::View view() const;
  void setFov(float yfovRadians) { fov_ = yfovRadians; }

  nlohmann::json save() const;
  void load(const nlohmann::json& j);

 private:
  glm::dvec3 forward() const;
  glm::dvec3 position_{0.0, 1.0, 5.0};
  double yaw_ = 0.0, pitch_ = 0.0;  // radians; yaw 0 looks down -Z
  double distance_ = 5.0;           // to the orbit pivot, along forward
  double sceneSize_ = 10.0;
  float fov_ = 0.9f, znear_ = 0.05f;
  // An orthographic view (a glTF orthographic camera) stays one: the dolly scales its height.
  bool orthographic_ = false;
  float orthoHalfHeight_ = 1.0f, zfar_ = 0.0f;
};

}  // namespace tl::editor
