#include "cli_args.h"

#include <fmt/format.h>

#include <cmath>
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
  unsigned w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w == 0 || h == 0)
    throw SessionError(fmt::format("--size `{}` is not WIDTHxHEIGHT (e.g. 640x360)", text));
  return {w, h};
}

glm::dvec3 parseVec3(const std::string& text, const char* what) {
  auto v = parseNumbers(text, what);
  if (v.size() != 3) throw SessionError(fmt::format("{} `{}` needs three numbers x,y,z", what, text));
  return {v[0], v[1], v[2]};
}

glm::vec3 parseColor(const std::string& text, const char* what) {
  auto v = parseNumbers(text, what);
  if (v.size() == 1) v = {v[0], v[0], v[0]};
  if (v.size() != 3) throw SessionError(fmt::format("{} `{}` needs one value or r,g,b", what, text));
  for (double c : v)
    if (c < 0.0) throw SessionError(fmt::format("{} `{}` must not be negative", what, text));
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
  if (a.fovDegrees) v.yfovRadians = float(*a.fovDegrees * M_PI / 180.0);
  session.setView(v);
}

void applyLight(tl::session::Session& session, const LightArgs& a) {
  tl::session::Lighting l = session.lighting();
  if (!a.sunDir.empty()) {
    glm::dvec3 d = parseVec3(a.sunDir, "--sun-dir");
    if (glm::length(d) < 1e-9) throw SessionError("--sun-dir must not be zero");
    l.sunDirection = glm::normalize(d);
  }
  if (!a.sun.empty()) l.sunIrradiance = parseColor(a.sun, "--sun");
  if (!a.sky.empty()) l.skyRadiance = parseColor(a.sky, "--sky");
  if (a.exposureEv) l.exposureEv = *a.exposureEv;
  session.setLighting(l);
}

int exitStatus(const tl::session::Session& session) {
  if (session.validationErrors() == 0) return 0;
  fmt::print(stderr, "twinlight: error: {} Vulkan validation error(s)\n", session.validationErrors());
  return 1;
}
