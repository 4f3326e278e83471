#include "lighting/common/emitter_table.h"

#include <algorithm>

namespace tl::lighting {

AliasTable buildAliasTable(const std::vector<double>& weights) {
  const size_t n = weights.size();
  AliasTable t;
  t.threshold.assign(n, 0.0f);
  t.alias.resize(n);
  t.probability.assign(n, 0.0);
  double total = 0.0;
  size_t heaviest = 0;
  for (size_t i = 0; i < n; ++i) {
    total += weights[i];
    if (weights[i] > weights[heaviest]) heaviest = i;
  }
  if (n == 0 || !(total > 0.0)) return t;
  // Vose's method: each slot's share of n, the small ones topped up from the large ones.
  std::vector<double> share(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    share[i] = weights[i] * double(n) / total;
    t.alias[i] = uint32_t(i);
    (share[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    t.threshold[s] = float(share[s]);
    t.alias[s] = l;
    share[l] -= 1.0 - share[s];
    if (share[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What rounding leaves: slots that should be full. A slot of weight 0 never keeps itself (it
  // may be left over when the rounding ran the large list dry first): it gives its whole
  // slot to the heaviest index.
  for (const auto* rest : {&small, &large})
    for (uint32_t i : *rest) {
      const bool empty = !(weights[i] > 0.0);
      t.threshold[i] = empty ? 0.0f : 1.0f;
      t.alias[i] = empty ? uint32_t(heaviest) : i;
    }
  // The probabilities the GPU's draw has, from the float thresholds it reads.
  for (size_t i = 0; i < n; ++i) {
    const double keep = std::clamp(double(t.threshold[i]), 0.0, 1.0);
    t.probability[i] += keep / double(n);
    t.probability[t.alias[i]] += (1.0 - keep) / double(n);
  }
  return t;
}

EmitterTable buildEmitterTable(const scene::Scene& scene, const std::vector<glm::vec3>& instanceEmission) {
  EmitterTable table;
  table.firstOfInstance.assign(scene.instances.size(), 0u);
  std::vector<double> power;  // area x luminance, per triangle
  for (size_t i = 0; i < scene.instances.size() && i < instanceEmission.size(); ++i) {
    const glm::vec3 radiance = instanceEmission[i];
    const double luminance = shared::tlLuminance(radiance);
    if (!(luminance > 0.0)) continue;
    const auto& inst = scene.instances[i];
    const auto& mesh = scene.meshes[inst.mesh];
    if (mesh.indices.size() < 3) continue;
    table.firstOfInstance[i] = uint32_t(table.entries.size()) + 1u;
    auto world = [&](uint32_t v) { return glm::dvec3(inst.transform * glm::dvec4(glm::dvec3(mesh.vertices[v].position), 1.0)); };
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::dvec3 p0 = world(mesh.indices[t]), p1 = world(mesh.indices[t + 1]), p2 = world(mesh.indices[t + 2]);
      const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
      shared::Emitter e{};
      e.p0 = glm::vec4(glm::vec3(p0), 0.0f);
      e.edge1 = glm::vec4(glm::vec3(p1 - p0), float(area));
      e.edge2 = glm::vec4(glm::vec3(p2 - p0), 0.0f);
      e.radiance = glm::vec4(radiance, 0.0f);
      e.ids = glm::uvec4(uint32_t(i), uint32_t(t / 3), 0u, 0u);
      table.entries.push_back(e);
      power.push_back(area > 0.0 ? area * luminance : 0.0);  // degenerate: cannot be hit either
      table.brightest = std::max({table.brightest, radiance.x, radiance.y, radiance.z});
    }
  }
  const AliasTable alias = buildAliasTable(power);
  if (alias.probability.empty() || !(alias.probability[0] >= 0.0) || power.empty()) return table;
  double total = 0.0;
  for (double p : power) total += p;
  if (!(total > 0.0)) {  // every triangle degenerate: nothing can be drawn or hit
    table = EmitterTable{{}, std::vector<uint32_t>(scene.instances.size(), 0u), 0.0f};
    return table;
  }
  for (size_t k = 0; k < table.entries.size(); ++k) {
    table.entries[k].p0.w = alias.threshold[k];
    table.entries[k].ids.z = alias.alias[k];
    table.entries[k].edge2.w = float(alias.probability[k]);
  }
  return table;
}

}  // namespace tl::lighting
