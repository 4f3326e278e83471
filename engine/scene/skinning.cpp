#include "scene/skinning.h"

namespace tl::scene {

std::vector<glm::mat4> jointMatrices(const Skin& skin, const glm::dmat4& meshNodeWorld,
                                     const std::vector<glm::dmat4>& nodeWorld) {
  const glm::dmat4 toMesh = glm::inverse(meshNodeWorld);
  std::vector<glm::mat4> out(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const glm::dmat4 joint = skin.joints[j] < nodeWorld.size() ? nodeWorld[skin.joints[j]] : glm::dmat4(1.0);
    const glm::dmat4 bind = j < skin.inverseBind.size() ? skin.inverseBind[j] : glm::dmat4(1.0);
    out[j] = glm::mat4(toMesh * joint * bind);  // composed in double: large worlds keep their precision
  }
  return out;
}

void skinVertices(const Mesh& mesh, const std::vector<glm::mat4>& joints, std::vector<Vertex>& vertices) {
  if (mesh.joints.size() != vertices.size() || mesh.weights.size() != vertices.size()) return;
  for (size_t v = 0; v < vertices.size(); ++v) {
    glm::mat4 m(0.0f);
    for (int k = 0; k < 4; ++k) {
      const float w = mesh.weights[v][k];
      if (w != 0.0f && mesh.joints[v][k] < joints.size()) m += w * joints[mesh.joints[v][k]];
    }
    Vertex& out = vertices[v];
    out.position = glm::vec3(m * glm::vec4(out.position, 1.0f));
    // The blended matrix's linear part: exact for rotations and uniform scales, the usual
    // approximation of linear blend skinning elsewhere.
    const glm::mat3 linear(m);
    const glm::vec3 n = linear * out.normal, t = linear * glm::vec3(out.tangent);
    const float nl = glm::length(n), tl = glm::length(t);
    out.normal = nl > 1e-12f ? n / nl : out.normal;
    if (tl > 1e-12f) out.tangent = glm::vec4(t / tl, out.tangent.w);
  }
}

}  // namespace tl::scene
