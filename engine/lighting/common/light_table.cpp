#include "lighting/common/light_table.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

namespace tl::lighting {

double lightSelectionPower(const scene::Light& light, double sceneScale) {
  const double luminance = shared::tlLuminance(light.radiometric());
  switch (light.type) {
    case scene::LightType::Point: return 4.0 * glm::pi<double>() * luminance;
    case scene::LightType::Spot: return 2.0 * glm::pi<double>() * (1.0 - std::cos(double(light.outerConeAngle))) * luminance;
    case scene::LightType::Directional: {
      const double radius = 0.5 * std::max(sceneScale, 1e-3);
      return glm::pi<double>() * radius * radius * luminance;
    }
    // A Lambertian face of radiance L and area A emits pi L A.
    case scene::LightType::Rect:
      return glm::pi<double>() * double(light.width) * double(light.height) * (light.twoSided ? 2.0 : 1.0) * luminance;
    case scene::LightType::Disk:
      return glm::pi<double>() * glm::pi<double>() * double(light.radius) * double(light.radius) * (light.twoSided ? 2.0 : 1.0) *
             luminance;
    case scene::LightType::Tube:  // the cylinder's side, 2 pi r length
      return glm::pi<double>() * 2.0 * glm::pi<double>() * double(light.radius) * double(light.length) * luminance;
  }
  return 0.0;
}

namespace {
// A unit vector perpendicular to unit n: `hint` made perpendicular, or any other where it is
// (nearly) parallel to n.
glm::dvec3 perpendicular(const glm::dvec3& n, const glm::dvec3& hint) {
  glm::dvec3 t = hint - n * glm::dot(n, hint);
  if (glm::length(t) < 1e-6 * std::max(glm::length(hint), 1e-300)) {
    t = std::abs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    t -= n * glm::dot(n, t);
  }
  return glm::normalize(t);
}

// The shape of an area light (shared/area_lights.h): half-extent vectors with u x v along the
// front normal, a tube's radius, two-sidedness.
void setAreaShape(shared::GpuLight& g, const scene::Light& l) {
  const glm::dvec3 n = glm::normalize(l.direction);
  const glm::dvec3 t = perpendicular(n, l.widthAxis), b = glm::cross(n, t);
  switch (l.type) {
    case scene::LightType::Rect:
      g.type = shared::kLightRect;
      g.axisU = glm::vec4(glm::vec3(t * (0.5 * l.width)), 0.0f);
      g.axisV = glm::vec4(glm::vec3(b * (0.5 * l.height)), l.twoSided ? 1.0f : 0.0f);
      break;
    case scene::LightType::Disk:
      g.type = shared::kLightDisk;
      g.axisU = glm::vec4(glm::vec3(t * double(l.radius)), 0.0f);
      g.axisV = glm::vec4(glm::vec3(b * double(l.radius)), l.twoSided ? 1.0f : 0.0f);
      break;
    default:  // Tube: the axis along direction
      g.type = shared::kLightTube;
      g.axisU = glm::vec4(glm::vec3(n * (0.5 * l.length)), l.radius);
      g.axisV = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
      break;
  }
}
}  // namespace

std::vector<shared::GpuLight> buildLightTable(const std::vector<scene::Light>& lights, const glm::dvec3& cameraWorld,
                                              double sceneScale) {
  std::vector<shared::GpuLight> table;
  std::vector<double> power;
  for (const auto& l : lights) {
    if (l.hidden) continue;  // hidden in the editor: kept in the lighting, not shaded
    const double p = lightSelectionPower(l, sceneScale);
    if (!(p > 0.0) || !std::isfinite(p)) continue;
    shared::GpuLight g{};
    g.position = glm::vec4(glm::vec3(l.position - cameraWorld), l.range.value_or(0.0f));
    g.direction = glm::vec4(glm::vec3(glm::normalize(l.direction)), 0.0f);
    g.intensity = glm::vec4(l.radiometric(), 0.0f);
    g.cosOuter = -1.0f;
    g.coneScale = 0.0f;
    switch (l.type) {
      case scene::LightType::Directional: g.type = shared::kLightDirectional; break;
      case scene::LightType::Point: g.type = shared::kLightPoint; break;
      case scene::LightType::Spot: {
        g.type = shared::kLightSpot;
        const double cosOuter = std::cos(double(l.outerConeAngle)), cosInner = std::cos(double(l.innerConeAngle));
        g.cosOuter = float(cosOuter);
        g.coneScale = float(1.0 / std::max(cosInner - cosOuter, 1e-3));
        break;
      }
      case scene::LightType::Rect:
      case scene::LightType::Disk:
      case scene::LightType::Tube:
        g.position.w = 0.0f;  // no range: an area light's falloff is its shape's
        setAreaShape(g, l);
        break;
    }
    table.push_back(g);
    power.push_back(p);
  }
  double total = 0.0;
  for (double p : power) total += p;
  double cumulative = 0.0;
  for (size_t i = 0; i < table.size(); ++i) {
    cumulative += power[i] / total;
    table[i].intensity.w = float(power[i] / total);
    table[i].direction.w = float(cumulative);
  }
  if (!table.empty()) table.back().direction.w = 1.0f;  // no gap a uniform can fall into
  return table;
}

}  // namespace tl::lighting
