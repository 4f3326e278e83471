// Skinning on the CPU (glTF 2.0 section 3.7.3): the joint matrices of a skinned mesh at a pose
// and the vertices they make. Pure; unit-tested against closed forms (tests/unit/test_skinning.cpp).
#pragma once

#include "scene/scene.h"

#include <vector>

namespace tl::scene {

// Per joint of `skin`: inverse(meshNodeWorld) * jointWorld * inverseBind, which takes a vertex
// of the mesh's bind pose to the mesh node's space (glTF ignores the mesh node's own transform
// for a skinned mesh; the instance applies meshNodeWorld again, so the world position is
// jointWorld * inverseBind * v as the specification says). `nodeWorld`: every node's world
// transform at the pose (nodeWorldTransformsAt).
std::vector<glm::mat4> jointMatrices(const Skin& skin, const glm::dmat4& meshNodeWorld,
                                     const std::vector<glm::dmat4>& nodeWorld);

// Skins `vertices` (the mesh's, already morphed if it morphs: glTF applies morph targets first)
// in place: positions by the weighted sum of the joints' matrices (linear blend skinning),
// normals and tangents by its linear part, renormalised.
void skinVertices(const Mesh& mesh, const std::vector<glm::mat4>& joints, std::vector<Vertex>& vertices);

}  // namespace tl::scene
