// glTF meshes: one Mesh per triangle primitive, with its vertex attributes (positions, normals,
// two UV sets, COLOR_0, tangents), morph targets and skin weights, each checked (finite, within
// the world's limits, as many as the vertices).
#include "scene/gltf_parts.h"
#include "scene/morph.h"

namespace tl::scene {
namespace {

// Positions (finite, within the world) and the triangle list (indices within the vertices).
void readTriangles(GltfImport& in, const tinygltf::Primitive& prim, size_t pi, Mesh& mesh) {
  const GltfReader& rd = in.rd;
  const std::string& name = mesh.name;
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) rd.fail(fmt::format("mesh `{}` primitive {} has no POSITION", name, pi));
  auto positions = rd.floats<3>(pos->second, "POSITION");
  mesh.vertices.resize(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    const auto& p = positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      rd.fail(fmt::format("mesh `{}` has a non-finite position (vertex {})", name, v));
    mesh.vertices[v].position = p;
    mesh.bounds.extend(glm::dvec3(p));
  }
  if (prim.indices >= 0) {
    mesh.indices = rd.indices(prim.indices);
  } else {
    mesh.indices.resize(positions.size());
    for (uint32_t v = 0; v < mesh.indices.size(); ++v) mesh.indices[v] = v;
  }
  if (mesh.indices.size() % 3 != 0) rd.fail(fmt::format("mesh `{}` has {} indices, not a multiple of 3", name, mesh.indices.size()));
  for (size_t k = 0; k < mesh.indices.size(); ++k)
    if (mesh.indices[k] >= mesh.vertices.size())
      rd.fail(fmt::format("mesh `{}` index {} is {}, beyond its {} vertices", name, k, mesh.indices[k], mesh.vertices.size()));
}

// Linear RGB or RGBA as float or normalized integers (glTF 3.7.2.1), multiplied into the base
// colour; each component is kept to [0, 1] like baseColorFactor.
void readVertexColours(GltfImport& in, int accessor, Mesh& mesh) {
  const GltfReader& rd = in.rd;
  const std::string& name = mesh.name;
  const bool rgba = accessor >= 0 && size_t(accessor) < in.model.accessors.size() &&
                    in.model.accessors[size_t(accessor)].type == TINYGLTF_TYPE_VEC4;
  std::vector<glm::vec4> colours;
  if (rgba) colours = rd.floats<4>(accessor, "COLOR_0");
  else for (const auto& c : rd.floats<3>(accessor, "COLOR_0")) colours.emplace_back(c, 1.0f);
  if (colours.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} COLOR_0 for {} vertices", name, colours.size(), mesh.vertices.size()));
  bool clampedAny = false;
  for (size_t v = 0; v < colours.size(); ++v) {
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(colours[v][c])) rd.fail(fmt::format("mesh `{}` has a non-finite COLOR_0 (vertex {})", name, v));
    const glm::vec4 kept = glm::clamp(colours[v], 0.0f, 1.0f);
    clampedAny |= kept != colours[v];
    mesh.vertices[v].color = kept;
  }
  if (clampedAny) in.values.warn(fmt::format("mesh `{}` has COLOR_0 components outside [0, 1]; they are clamped", name));
}

// Normals, UV sets, colours and tangents as the file gives them; which of normals and tangents
// it gave (the rest are generated: finishVertices).
struct GivenAttributes {
  bool normals = false, tangents = false;
};
GivenAttributes readVertexAttributes(GltfImport& in, const tinygltf::Primitive& prim, Mesh& mesh) {
  const GltfReader& rd = in.rd;
  const std::string& name = mesh.name;
  GivenAttributes given;
  if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
    auto normals = rd.floats<3>(it->second, "NORMAL");
    if (normals.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} normals for {} vertices", name, normals.size(), mesh.vertices.size()));
    for (size_t v = 0; v < normals.size(); ++v) mesh.vertices[v].normal = normals[v];
    given.normals = true;
  }
  if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
    auto uvs = rd.floats<2>(it->second, "TEXCOORD_0");
    if (uvs.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} UVs for {} vertices", name, uvs.size(), mesh.vertices.size()));
    for (size_t v = 0; v < uvs.size(); ++v) mesh.vertices[v].uv = uvs[v];
  }
  if (auto it = prim.attributes.find("TEXCOORD_1"); it != prim.attributes.end()) {
    auto uvs = rd.floats<2>(it->second, "TEXCOORD_1");
    if (uvs.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} TEXCOORD_1 for {} vertices", name, uvs.size(), mesh.vertices.size()));
    for (size_t v = 0; v < uvs.size(); ++v) mesh.vertices[v].uv1 = uvs[v];
  }
  if (auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) readVertexColours(in, it->second, mesh);
  if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
    auto tangents = rd.floats<4>(it->second, "TANGENT");
    if (tangents.size() == mesh.vertices.size()) {
      for (size_t v = 0; v < tangents.size(); ++v) mesh.vertices[v].tangent = tangents[v];
      given.tangents = true;
    }
  }
  return given;
}

// Morph targets: displacements of positions (and normals) added with weights. `vertexSource`:
// the file's vertex each of the mesh's came from (finishVertices may split some).
void readMorphTargets(GltfImport& in, const tinygltf::Primitive& prim, size_t fileVertices,
                      const std::vector<uint32_t>& vertexSource, Mesh& mesh) {
  const GltfReader& rd = in.rd;
  const std::string& name = mesh.name;
  for (size_t ti = 0; ti < prim.targets.size(); ++ti) {
    MorphTarget target;
    target.positions.assign(mesh.vertices.size(), glm::vec3(0.0f));
    for (const auto& [attribute, index] : prim.targets[ti]) {
      if (attribute != "POSITION" && attribute != "NORMAL") continue;  // tangent deltas are not applied
      auto deltas = rd.floats<3>(index, "morph target");
      if (deltas.size() != fileVertices)
        rd.fail(fmt::format("mesh `{}` morph target {} has {} {} deltas for {} vertices", name, ti, deltas.size(),
                            attribute, fileVertices));
      for (const auto& d : deltas)
        if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) ||
            std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) > InputLimits::kMaxCoordinate)
          rd.fail(fmt::format("mesh `{}` morph target {} has a non-finite or out-of-range {} delta", name, ti, attribute));
      // Vertices split for their tangents take their original's deltas.
      std::vector<glm::vec3> perVertex(mesh.vertices.size());
      for (size_t k = 0; k < perVertex.size(); ++k) perVertex[k] = deltas[vertexSource[k]];
      (attribute == "POSITION" ? target.positions : target.normals) = std::move(perVertex);
    }
    mesh.morphTargets.push_back(std::move(target));
  }
}

// Skinning: four joints and weights per vertex; the node's skin says whose joints they are.
void readSkinWeights(GltfImport& in, const tinygltf::Primitive& prim, size_t fileVertices,
                     const std::vector<uint32_t>& vertexSource, Mesh& mesh) {
  const GltfReader& rd = in.rd;
  const std::string& name = mesh.name;
  const auto jointsAttribute = prim.attributes.find("JOINTS_0"), weightsAttribute = prim.attributes.find("WEIGHTS_0");
  if (jointsAttribute == prim.attributes.end() || weightsAttribute == prim.attributes.end()) return;
  const auto joints = rd.floats<4>(jointsAttribute->second, "JOINTS_0");
  const auto weights = rd.floats<4>(weightsAttribute->second, "WEIGHTS_0");
  if (joints.size() != fileVertices || weights.size() != fileVertices)
    rd.fail(fmt::format("mesh `{}` has {} JOINTS_0 and {} WEIGHTS_0 for {} vertices", name, joints.size(), weights.size(),
                        fileVertices));
  for (size_t k = 0; k < mesh.vertices.size(); ++k) {
    const size_t v = vertexSource[k];
    glm::vec4 w = weights[v];
    for (int c = 0; c < 4; ++c)
      if (!(w[c] >= 0.0f) || !std::isfinite(w[c]) || !(joints[v][c] >= 0.0f && joints[v][c] <= 65535.0f))
        rd.fail(fmt::format("mesh `{}` vertex {} has a joint or weight that is negative or not finite", name, v));
    const float sum = w.x + w.y + w.z + w.w;
    if (!(sum > 0.0f)) rd.fail(fmt::format("mesh `{}` vertex {} has weights that sum to 0", name, v));
    mesh.joints.push_back(glm::u16vec4(joints[v]));
    mesh.weights.push_back(w / sum);  // glTF asks for a sum of 1; exporters round
  }
}

// One triangle primitive of glTF mesh `gmesh` as a Mesh, its material not yet set.
Mesh readPrimitive(GltfImport& in, const tinygltf::Mesh& gmesh, const tinygltf::Primitive& prim, size_t pi,
                   std::string name) {
  Mesh mesh;
  mesh.name = std::move(name);
  readTriangles(in, prim, pi, mesh);
  const GivenAttributes given = readVertexAttributes(in, prim, mesh);
  const size_t fileVertices = mesh.vertices.size();
  const std::vector<uint32_t> vertexSource = finishVertices(mesh, given.normals, given.tangents);
  readMorphTargets(in, prim, fileVertices, vertexSource, mesh);
  readSkinWeights(in, prim, fileVertices, vertexSource, mesh);
  if (!withinWorld(mesh.bounds))
    in.rd.fail(fmt::format("mesh `{}` has positions beyond {:g} m from its origin", mesh.name, InputLimits::kMaxCoordinate));
  if (!mesh.morphTargets.empty()) {
    mesh.morphWeights.assign(mesh.morphTargets.size(), 0.0f);
    for (size_t k = 0; k < gmesh.weights.size() && k < mesh.morphWeights.size(); ++k)
      mesh.morphWeights[k] = in.values.morphWeight(gmesh.weights[k], fmt::format("mesh `{}` weight {}", mesh.name, k));
    mesh.bounds = morphBounds(mesh);
  }
  return mesh;
}

}  // namespace

std::vector<std::vector<uint32_t>> readMeshes(GltfImport& in, uint32_t defaultMaterial, bool& usedDefault) {
  std::vector<std::vector<uint32_t>> meshPrimitives(in.model.meshes.size());
  for (size_t mi = 0; mi < in.model.meshes.size(); ++mi) {
    const auto& gmesh = in.model.meshes[mi];
    for (size_t pi = 0; pi < gmesh.primitives.size(); ++pi) {
      const auto& prim = gmesh.primitives[pi];
      std::string name = gmesh.name.empty() ? fmt::format("mesh{}", mi) : gmesh.name;
      if (pi > 0) name += fmt::format("#{}", pi);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // IgnoredFeatures says so
      Mesh mesh = readPrimitive(in, gmesh, prim, pi, std::move(name));
      if (prim.material >= 0 && size_t(prim.material) < in.scene.materials.size()) {
        mesh.material = uint32_t(prim.material);
      } else {
        mesh.material = defaultMaterial;
        usedDefault = true;
      }
      mesh.contentHash = hashMesh(mesh);
      meshPrimitives[mi].push_back(uint32_t(in.scene.meshes.size()));
      in.scene.meshes.push_back(std::move(mesh));
    }
  }
  return meshPrimitives;
}

}  // namespace tl::scene
