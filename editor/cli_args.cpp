#include "cli_args.h"

#include "scene/environment_map.h"
#include "scene/input_limits.h"
#include "session/lighting_file.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

using tl::session::SessionError;

namespace {

std::vector<double> parseNumbers(const std::string& text, const char* what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ',')) {
    try {
      size_t used = 0;
      double v = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(v)) throw std::invalid_argument(part);
      out.push_back(v);
    } catch (const std::exception&) {
      throw SessionError(fmt::format("{} `{}` is not a list of numbers", what, text));
    }
  }
  return out;
}

}  // namespace

std::pair<uint32_t, uint32_t> parseSize(const std::string& text) {
  // Digits only, read into 64 bits: sscanf's %u would take "-5" and wrap 4294967344 to 48.
  const auto bad = [&] { return SessionError(fmt::format("--size `{}` is not WIDTHxHEIGHT (e.g. 640x360)", text)); };
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos || x == 0 || x + 1 == text.size()) throw bad();
  uint64_t side[2] = {0, 0};
  const std::string parts[2] = {text.substr(0, x), text.substr(x + 1)};
  for (int i = 0; i < 2; ++i) {
    const std::string& p = parts[i];
    if (p.find_first_not_of("0123456789") != std::string::npos || p.size() > 12) throw bad();
    std::from_chars(p.data(), p.data() + p.size(), side[i]);
  }
  if (side[0] == 0 || side[1] == 0 || side[0] > kMaxImageSide || side[1] > kMaxImageSide)
    throw SessionError(fmt::format("--size `{}` is out of range: each side 1 to {} pixels", text, kMaxImageSide));
  return {uint32_t(side[0]), uint32_t(side[1])};
}

glm::dvec3 parseVec3(const std::string& text, const char* what) {
  auto v = parseNumbers(text, what);
  if (v.size() != 3) throw SessionError(fmt::format("{} `{}` needs three numbers x,y,z", what, text));
  for (double c : v)
    if (std::abs(c) > tl::scene::InputLimits::kMaxCoordinate)
      throw SessionError(fmt::format("{} `{}` is out of range: at most {:g} in magnitude", what, text,
                                     tl::scene::InputLimits::kMaxCoordinate));
  return {v[0], v[1], v[2]};
}

glm::vec3 parseColor(const std::string& text, const char* what) {
  auto v = parseNumbers(text, what);
  if (v.size() == 1) v = {v[0], v[0], v[0]};
  if (v.size() != 3) throw SessionError(fmt::format("{} `{}` needs one value or r,g,b", what, text));
  for (double c : v) {
    if (c < 0.0) throw SessionError(fmt::format("{} `{}` must not be negative", what, text));
    if (c > tl::scene::InputLimits::kMaxLight)
      throw SessionError(fmt::format("{} `{}` is out of range: at most {:g}", what, text, tl::scene::InputLimits::kMaxLight));
  }
  return {float(v[0]), float(v[1]), float(v[2])};
}

void applyView(tl::session::Session& session, const ViewArgs& a) {
  if (a.camera && (!a.lookFrom.empty() || !a.lookAt.empty()))
    throw SessionError("--camera and --look-from/--look-at cannot be combined");
  if (a.camera) session.useSceneCamera(*a.camera);
  tl::session::View v = session.view();
  if (!a.lookFrom.empty() || !a.lookAt.empty()) {
    if (a.lookFrom.empty() || a.lookAt.empty()) throw SessionError("--look-from and --look-at go together");
    v.position = parseVec3(a.lookFrom, "--look-from");
    glm::dvec3 target = parseVec3(a.lookAt, "--look-at");
    if (glm::length(target - v.position) < 1e-9) throw SessionError("--look-from and --look-at are the same point");
    v.forward = target - v.position;
    v.up = {0.0, 1.0, 0.0};
  }
  if (a.fovDegrees) {
    if (!(*a.fovDegrees > 0.0f && *a.fovDegrees < 178.0f))
      throw SessionError(fmt::format("--fov {} is out of range: more than 0 and less than 178 degrees", *a.fovDegrees));
    v.yfovRadians = float(*a.fovDegrees * M_PI / 180.0);
  }
  session.setView(v);
}

void applyLight(tl::session::Session& session, const LightArgs& a) {
  tl::session::Lighting l = session.lighting();
  if (!a.lighting.empty()) l = tl::session::readLightingFile(a.lighting, l);
  if (!a.sunDir.empty()) {
    glm::dvec3 d = parseVec3(a.sunDir, "--sun-dir");
    if (glm::length(d) < 1e-9) throw SessionError("--sun-dir must not be zero");
    l.sunDirection = glm::normalize(d);
  }
  if (!a.sun.empty()) l.sunIrradiance = parseColor(a.sun, "--sun");
  if (!a.sky.empty()) l.skyRadiance = parseColor(a.sky, "--sky");
  if (!a.environment.empty()) {
    try {
      l.environmentMap = std::make_shared<const tl::scene::EnvironmentMap>(tl::scene::loadEnvironmentMap(a.environment));
    } catch (const tl::scene::SceneError& e) {
      throw SessionError(e.what());
    }
  }
  if ((a.environmentRotation || a.environmentIntensity) && !l.environmentMap)
    throw SessionError("--environment-rotation and --environment-intensity need --environment FILE");
  if (a.environmentRotation) {
    if (!std::isfinite(*a.environmentRotation) || std::abs(*a.environmentRotation) > 360.0f)
      throw SessionError(fmt::format("--environment-rotation {} is out of range: -360 to 360 degrees", *a.environmentRotation));
    l.environmentRotation = float(*a.environmentRotation * M_PI / 180.0);
  }
  if (a.environmentIntensity) {
    if (!(*a.environmentIntensity >= 0.0f && *a.environmentIntensity <= 1e6f))
      throw SessionError(fmt::format("--environment-intensity {} is out of range: 0 to 1e6", *a.environmentIntensity));
    l.environmentIntensity = *a.environmentIntensity;
  }
  if (a.exposureEv) {
    const float most = tl::scene::InputLimits::kMaxExposureEv;
    if (!(std::abs(*a.exposureEv) <= most))
      throw SessionError(fmt::format("--exposure {} is out of range: a finite EV from {:g} to {:g}", *a.exposureEv, -most, most));
    l.exposureEv = *a.exposureEv;
  }
  session.setLighting(l);
}

int exitStatus(const tl::session::Session& session) {
  if (session.validationErrors() == 0) return 0;
  fmt::print(stderr, "twinlight: error: {} Vulkan validation error(s)\n", session.validationErrors());
  return 1;
}
