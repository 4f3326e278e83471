#include "scene/morph.h"

#include "scene/node_animation.h"

#include <algorithm>
#include <cmath>

namespace tl::scene {

std::vector<std::vector<float>> morphWeightsAt(const Scene& scene, double seconds) {
  std::vector<std::vector<float>> weights(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (scene.meshes[m].deforms()) weights[m] = scene.meshes[m].morphWeights;
  const double t = loopedAnimationTime(scene, seconds);
  for (const MorphAnimation& a : scene.morphAnimations) {
    if (a.mesh >= scene.meshes.size() || a.times.empty()) continue;
    const size_t targets = scene.meshes[a.mesh].morphTargets.size();
    if (targets == 0 || a.weights.size() != a.times.size() * targets) continue;
    std::vector<float>& w = weights[a.mesh];
    w.resize(targets, 0.0f);
    // The key at or before t, and how far t is towards the next (clamped at both ends).
    const KeySpan span = keySpan(a.times, t);
    const size_t lo = span.lo, hi = span.hi;
    const float f = a.step ? 0.0f : float(span.f);
    for (size_t k = 0; k < targets; ++k)
      w[k] = a.weights[lo * targets + k] + f * (a.weights[hi * targets + k] - a.weights[lo * targets + k]);
  }
  return weights;
}

void deformVertices(const Mesh& mesh, const std::vector<float>& weights, std::vector<Vertex>& out) {
  out = mesh.vertices;
  for (size_t k = 0; k < mesh.morphTargets.size() && k < weights.size(); ++k) {
    const float w = weights[k];
    if (w == 0.0f) continue;
    const MorphTarget& t = mesh.morphTargets[k];
    for (size_t v = 0; v < out.size(); ++v) {
      out[v].position += w * t.positions[v];
      if (!t.normals.empty()) out[v].normal += w * t.normals[v];
    }
  }
  for (auto& v : out) {
    const float len = glm::length(v.normal);
    v.normal = len > 1e-12f ? v.normal / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

Bounds morphBounds(const Mesh& mesh) {
  Bounds b;
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    glm::vec3 lo = mesh.vertices[v].position, hi = lo;
    for (const MorphTarget& t : mesh.morphTargets) {
      lo -= glm::abs(t.positions[v]);
      hi += glm::abs(t.positions[v]);
    }
    b.extend(glm::dvec3(lo));
    b.extend(glm::dvec3(hi));
  }
  return b;
}

}  // namespace tl::scene
