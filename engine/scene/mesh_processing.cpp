#include "scene/scene_internal.h"

#include <cmath>

namespace tl::scene {
namespace {

bool usable(const glm::vec3& v) {
  float l = glm::length(v);
  return std::isfinite(l) && l > 1e-12f;
}

// Any unit vector perpendicular to n (Duff et al. 2017 branchless basis).
glm::vec3 perpendicular(const glm::vec3& n) {
  float s = std::copysign(1.0f, n.z);
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  return glm::vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}

}  // namespace

void finishVertices(Mesh& mesh, bool haveNormals, bool haveTangents) {
  auto& v = mesh.vertices;
  const auto& idx = mesh.indices;
  std::vector<glm::vec3> faceNormalSum(v.size(), glm::vec3(0.0f)), tan(v.size(), glm::vec3(0.0f)), bit(v.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    uint32_t i0 = idx[t], i1 = idx[t + 1], i2 = idx[t + 2];
    glm::vec3 e1 = v[i1].position - v[i0].position, e2 = v[i2].position - v[i0].position;
    glm::vec3 n = glm::cross(e1, e2);  // length = 2 * area: area weighting for free
    glm::vec2 d1 = v[i1].uv - v[i0].uv, d2 = v[i2].uv - v[i0].uv;
    float det = d1.x * d2.y - d2.x * d1.y;
    glm::vec3 tangent(0.0f), bitangent(0.0f);
    if (std::abs(det) > 1e-20f) {
      float r = 1.0f / det;
      tangent = (e1 * d2.y - e2 * d1.y) * r;
      bitangent = (e2 * d1.x - e1 * d2.x) * r;
    }
    for (uint32_t i : {i0, i1, i2}) {
      if (usable(n)) faceNormalSum[i] += n;
      if (usable(tangent) && usable(bitangent)) tan[i] += tangent, bit[i] += bitangent;
    }
  }
  for (size_t i = 0; i < v.size(); ++i) {
    glm::vec3 n = haveNormals ? v[i].normal : faceNormalSum[i];
    if (!usable(n)) n = usable(faceNormalSum[i]) ? faceNormalSum[i] : glm::vec3(0.0f, 1.0f, 0.0f);
    n = glm::normalize(n);
    v[i].normal = n;
    glm::vec3 t = haveTangents ? glm::vec3(v[i].tangent) : tan[i];
    float w = haveTangents ? (v[i].tangent.w < 0.0f ? -1.0f : 1.0f) : 1.0f;
    t -= n * glm::dot(n, t);  // Gram-Schmidt against the normal
    if (!usable(t)) t = perpendicular(n);
    t = glm::normalize(t);
    if (!haveTangents && usable(bit[i])) w = glm::dot(glm::cross(n, t), bit[i]) < 0.0f ? -1.0f : 1.0f;
    v[i].tangent = glm::vec4(t, w);
  }
  mesh.generatedTangents = !haveTangents;
}

Bounds transformBounds(const Bounds& local, const glm::dmat4& m) {
  Bounds out;
  if (!local.valid()) return out;
  for (int i = 0; i < 8; ++i) out.extend(glm::dvec3(m * glm::dvec4(local.corner(i), 1.0)));
  return out;
}

}  // namespace tl::scene
