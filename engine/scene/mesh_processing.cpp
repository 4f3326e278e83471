#include "scene/scene_internal.h"

#include <cmath>
#include <map>

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

glm::vec3 projectOnPlane(const glm::vec3& v, const glm::vec3& n) { return v - n * glm::dot(n, v); }

// The angle at corner p between the edges to a and b, measured in the plane of the normal n.
float cornerAngle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& n) {
  glm::vec3 e1 = projectOnPlane(a - p, n), e2 = projectOnPlane(b - p, n);
  if (!usable(e1) || !usable(e2)) return 0.0f;
  return std::acos(glm::clamp(glm::dot(glm::normalize(e1), glm::normalize(e2)), -1.0f, 1.0f));
}

}  // namespace

// Tangents follow MikkTSpace (M. Mikkelsen, "Simulation of wrinkled surfaces revisited",
// 2008, and the description in the header of its reference implementation, mikktspace.c), which is what Blender, Substance and the glTF
// sample models write, on the texture coordinates as those tools see them: v up. glTF
// stores v down (v_gltf = 1 - v), so the bitangent the normal map's green channel follows is
// -dP/dv_gltf, and the handedness is the sign of the UV area in that flipped space.
//  - per triangle: the UV gradient dP/du and the orientation (sign of the flipped UV area);
//  - per corner: dP/du projected onto the plane of the vertex normal, normalized, weighted by
//    the corner's angle in that plane;
//  - corners of one vertex are summed per orientation: a vertex whose triangles disagree (a
//    UV mirror seam) is split in two, each with its own handedness.
std::vector<uint32_t> finishVertices(Mesh& mesh, bool haveNormals, bool haveTangents) {
  auto& v = mesh.vertices;
  auto& idx = mesh.indices;
  std::vector<uint32_t> source(v.size());
  for (uint32_t i = 0; i < source.size(); ++i) source[i] = i;

  // Normals first: the tangents are projected onto them.
  std::vector<glm::vec3> faceNormalSum(v.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    uint32_t i0 = idx[t], i1 = idx[t + 1], i2 = idx[t + 2];
    glm::vec3 n = glm::cross(v[i1].position - v[i0].position, v[i2].position - v[i0].position);  // |n| = 2 area
    if (!usable(n)) continue;
    for (uint32_t i : {i0, i1, i2}) faceNormalSum[i] += n;
  }
  for (size_t i = 0; i < v.size(); ++i) {
    glm::vec3 n = haveNormals ? v[i].normal : faceNormalSum[i];
    if (!usable(n)) n = usable(faceNormalSum[i]) ? faceNormalSum[i] : glm::vec3(0.0f, 1.0f, 0.0f);
    v[i].normal = glm::normalize(n);
  }

  if (haveTangents) {
    // Used as given (glTF: w is the handedness); only made unit and perpendicular to the normal.
    for (auto& vertex : v) {
      glm::vec3 t = projectOnPlane(glm::vec3(vertex.tangent), vertex.normal);
      if (!usable(t)) t = perpendicular(vertex.normal);
      vertex.tangent = glm::vec4(glm::normalize(t), vertex.tangent.w < 0.0f ? -1.0f : 1.0f);
    }
    mesh.generatedTangents = false;
    return source;
  }

  // Per (vertex, orientation): the angle-weighted sum of the corners' tangent directions.
  std::vector<glm::vec3> sum[2] = {std::vector<glm::vec3>(v.size(), glm::vec3(0.0f)),
                                   std::vector<glm::vec3>(v.size(), glm::vec3(0.0f))};  // [negative, positive]
  std::vector<uint8_t> used[2] = {std::vector<uint8_t>(v.size(), 0), std::vector<uint8_t>(v.size(), 0)};
  std::vector<int8_t> cornerOrientation(idx.size(), 0);  // +1, -1; 0: no usable UV gradient
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    const uint32_t c[3] = {idx[t], idx[t + 1], idx[t + 2]};
    glm::vec3 e1 = v[c[1]].position - v[c[0]].position, e2 = v[c[2]].position - v[c[0]].position;
    // UVs with v flipped (tools' convention), as differences: (du, -dv).
    glm::vec2 d1 = v[c[1]].uv - v[c[0]].uv, d2 = v[c[2]].uv - v[c[0]].uv;
    d1.y = -d1.y, d2.y = -d2.y;
    const float area = d1.x * d2.y - d2.x * d1.y;  // twice the signed UV area
    if (!(std::abs(area) > 1e-20f) || !std::isfinite(area)) continue;
    const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / area;
    if (!usable(dPdu)) continue;
    const bool positive = area > 0.0f;
    for (int k = 0; k < 3; ++k) {
      const Vertex& p = v[c[k]];
      glm::vec3 dir = projectOnPlane(dPdu, p.normal);
      if (!usable(dir)) continue;
      const float angle = cornerAngle(p.position, v[c[(k + 1) % 3]].position, v[c[(k + 2) % 3]].position, p.normal);
      sum[positive][c[k]] += glm::normalize(dir) * angle;
      used[positive][c[k]] = 1;
      cornerOrientation[t + size_t(k)] = positive ? 1 : -1;
    }
  }

  // A vertex used with both orientations keeps the positive one and gets a copy for the other.
  const size_t firstCopy = v.size();
  std::map<uint32_t, uint32_t> negativeCopy;
  for (size_t k = 0; k < idx.size(); ++k) {
    const uint32_t i = idx[k];
    if (cornerOrientation[k] >= 0 || i >= firstCopy || !used[1][i]) continue;
    auto [it, inserted] = negativeCopy.try_emplace(i, uint32_t(v.size()));
    if (inserted) {
      v.push_back(v[i]);
      source.push_back(source[i]);
    }
    idx[k] = it->second;
  }
  for (size_t i = 0; i < v.size(); ++i) {
    const uint32_t original = source[i];
    // Copies and vertices only negative corners use take the negative sum.
    const bool negative = i >= firstCopy || (!used[1][original] && used[0][original]);
    glm::vec3 t = sum[negative ? 0 : 1][original];
    const float w = negative ? -1.0f : 1.0f;
    if (!usable(t)) t = perpendicular(v[i].normal);
    v[i].tangent = glm::vec4(glm::normalize(t), w);
  }
  mesh.generatedTangents = true;
  return source;
}

Bounds transformBounds(const Bounds& local, const glm::dmat4& m) {
  Bounds out;
  if (!local.valid()) return out;
  for (int i = 0; i < 8; ++i) out.extend(glm::dvec3(m * glm::dvec4(local.corner(i), 1.0)));
  return out;
}

}  // namespace tl::scene
