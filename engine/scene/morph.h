// Morph-target deformation on the CPU: the weights the scene's animations give each
// deforming mesh at a time, and the vertices those weights make. Pure; unit-tested against
// closed forms.
#pragma once

#include "scene/scene.h"

#include <vector>

namespace tl::scene {

// Weights of every mesh at `seconds` (looping over scene.animationSeconds): the animated
// value where a channel drives the mesh, its morphWeights otherwise; empty for meshes that
// do not deform.
std::vector<std::vector<float>> morphWeightsAt(const Scene& scene, double seconds);

// The mesh's vertices under `weights`: position + sum(w * delta), normal likewise then
// renormalised; tangents and UVs as stored.
void deformVertices(const Mesh& mesh, const std::vector<float>& weights, std::vector<Vertex>& out);

// Bounds holding every pose with weights in [-1, 1] (per vertex and axis, the base plus or
// minus the deltas' sizes): what culling and the voxel clipmap may rely on.
Bounds morphBounds(const Mesh& mesh);

}  // namespace tl::scene
