#include "lighting/rt/emitters.h"

namespace tl::lighting {

std::vector<shared::RtEmitter> buildEmitterTable(const scene::Scene& scene, const std::vector<glm::vec3>& instanceEmission) {
  std::vector<shared::RtEmitter> table;
  std::vector<double> power;  // area x luminance, per triangle
  for (size_t i = 0; i < scene.instances.size() && i < instanceEmission.size(); ++i) {
    const glm::vec3 radiance = instanceEmission[i];
    const double luminance = shared::tlLuminance(radiance);
    if (!(luminance > 0.0)) continue;
    const auto& inst = scene.instances[i];
    const auto& mesh = scene.meshes[inst.mesh];
    auto world = [&](uint32_t v) { return glm::dvec3(inst.transform * glm::dvec4(glm::dvec3(mesh.vertices[v].position), 1.0)); };
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::dvec3 p0 = world(mesh.indices[t]), p1 = world(mesh.indices[t + 1]), p2 = world(mesh.indices[t + 2]);
      const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
      if (!(area > 0.0)) continue;  // degenerate: cannot be hit either
      shared::RtEmitter e{};
      e.p0 = glm::vec4(glm::vec3(p0), 0.0f);
      e.edge1 = glm::vec4(glm::vec3(p1 - p0), float(area));
      e.edge2 = glm::vec4(glm::vec3(p2 - p0), 0.0f);
      e.radiance = glm::vec4(radiance, 0.0f);
      table.push_back(e);
      power.push_back(area * luminance);
    }
  }
  double total = 0.0;
  for (double p : power) total += p;
  double cumulative = 0.0;
  for (size_t i = 0; i < table.size(); ++i) {
    const double probability = power[i] / total;
    cumulative += probability;
    table[i].edge2.w = float(probability);
    table[i].p0.w = float(cumulative);
  }
  if (!table.empty()) table.back().p0.w = 1.0f;  // rounding must not leave a gap a uniform can fall into
  return table;
}

}  // namespace tl::lighting
