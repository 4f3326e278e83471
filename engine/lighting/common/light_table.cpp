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
  }
  return 0.0;
}

std::vector<shared::GpuLight> buildLightTable(const std::vector<scene::Light>& lights, const glm::dvec3& cameraWorld,
                                              double sceneScale) {
  std::vector<shared::GpuLight> table;
  std::vector<double> power;
  for (const auto& l : lights) {
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
