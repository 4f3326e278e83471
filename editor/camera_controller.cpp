#include "camera_controller.h"

#include <algorithm>
#include <cmath>

namespace tl::editor {

glm::dvec3 CameraController::forward() const {
  return {-std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

void CameraController::reset(const session::View& v, double sceneSize) {
  sceneSize_ = std::max(sceneSize, 1e-3);
  position_ = v.position;
  glm::dvec3 f = glm::normalize(v.forward);
  pitch_ = std::asin(std::clamp(f.y, -1.0, 1.0));
  yaw_ = std::atan2(-f.x, -f.z);
  distance_ = sceneSize_ * 0.3;
  fov_ = v.yfovRadians;
  znear_ = v.znear;
  orthographic_ = v.orthographic;
  orthoHalfHeight_ = v.orthoHalfHeight;
  zfar_ = v.zfar;
}

void CameraController::update(const CameraInput& in) {
  const double rotate = 0.005;  // radians per pixel
  const double limit = 1.55;
  if (in.orbitDelta != glm::vec2(0.0f)) {
    glm::dvec3 pivot = position_ + forward() * distance_;
    yaw_ -= in.orbitDelta.x * rotate;
    pitch_ = std::clamp(pitch_ - in.orbitDelta.y * rotate, -limit, limit);
    position_ = pivot - forward() * distance_;
  }
  if (in.lookDelta != glm::vec2(0.0f)) {
    yaw_ -= in.lookDelta.x * rotate;
    pitch_ = std::clamp(pitch_ - in.lookDelta.y * rotate, -limit, limit);
  }
  glm::dvec3 f = forward();
  glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
  glm::dvec3 up = glm::cross(right, f);
  if (in.panDelta != glm::vec2(0.0f)) {
    double perPixel = distance_ * 0.0015;
    position_ += (-right * double(in.panDelta.x) + up * double(in.panDelta.y)) * perPixel;
  }
  if (in.dolly != 0.0f && orthographic_) {
    // Moving along the axis changes nothing an orthographic view sees: zoom its height.
    const double zoomed = double(orthoHalfHeight_) * std::pow(0.85, double(in.dolly));
    orthoHalfHeight_ = float(std::clamp(zoomed, sceneSize_ * 1e-3, sceneSize_ * 10.0));
  } else if (in.dolly != 0.0f) {
    double step = std::max(distance_ * 0.15, sceneSize_ * 0.005) * in.dolly;
    position_ += f * step;
    distance_ = std::max(distance_ - step, sceneSize_ * 0.01);
  }
  if (in.move != glm::vec3(0.0f)) {
    double speed = sceneSize_ * 0.15 * (in.fast ? 4.0 : 1.0);  // metres per second
    position_ += (right * double(in.move.x) + glm::dvec3(0, 1, 0) * double(in.move.y) + f * double(in.move.z)) *
                 (speed * in.seconds);
  }
}

void CameraController::translate(const glm::dvec3& d) {
  const glm::dvec3 f = forward();
  const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, f);
  position_ += right * d.x + up * d.y + f * d.z;
}

void CameraController::focus(const scene::Bounds& b) {
  if (!b.valid()) return;
  double radius = std::max(0.5 * glm::length(b.size()), 1e-3);
  distance_ = radius / std::sin(0.5 * fov_) * 1.1;
  position_ = b.center() - forward() * distance_;
}

session::View CameraController::view() const {
  session::View v;
  v.position = position_;
  v.forward = forward();
  v.up = {0, 1, 0};
  v.yfovRadians = fov_;
  v.znear = znear_;
  v.orthographic = orthographic_;
  v.orthoHalfHeight = orthoHalfHeight_;
  v.zfar = zfar_;
  return v;
}

nlohmann::json CameraController::save() const {
  return {{"position", {position_.x, position_.y, position_.z}}, {"yaw", yaw_}, {"pitch", pitch_}, {"distance", distance_}};
}

void CameraController::load(const nlohmann::json& j) {
  auto p = j.at("position");
  position_ = {p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()};
  yaw_ = j.at("yaw").get<double>();
  pitch_ = j.at("pitch").get<double>();
  distance_ = j.at("distance").get<double>();
}

}  // namespace tl::editor
