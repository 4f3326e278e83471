// The scene's emissive triangles as both ray tracers sample them (shared/emitters.h): every
// triangle of every instance whose material emits, in the mesh's order, each chosen in
// proportion to its power (area x the luminance of the material's average emission) through an
// alias table. Pure, tested without a GPU.
#pragma once

#include "scene/scene.h"
#include "shared/emitters.h"

#include <glm/glm.hpp>

#include <vector>

namespace tl::lighting {

struct EmitterTable {
  // One entry per triangle of each emitting instance (a degenerate one with probability 0);
  // empty when nothing emits.
  std::vector<shared::Emitter> entries;
  // Per instance: its first entry + 1, or 0 for an instance that emits nothing. A hit on
  // triangle t of instance i is entry firstOfInstance[i] - 1 + t.
  std::vector<uint32_t> firstOfInstance;
  float brightest = 0.0f;  // the largest channel of any entry's radiance
};

// `instanceEmission`: each instance's average emitted radiance (rgb). Deforming meshes are
// taken in their rest pose, world space at the instances' transforms.
EmitterTable buildEmitterTable(const scene::Scene& scene, const std::vector<glm::vec3>& instanceEmission);

// The alias table over `weights` (>= 0, not all 0): per slot its threshold and its alias, and
// the probability each index is drawn with exactly, as tlAliasSlot / tlAliasKeepsSlot draw
// with the thresholds rounded to float: (threshold_i + sum over slots j aliased to i of
// (1 - threshold_j)) / n. An index of weight 0 is never drawn.
struct AliasTable {
  std::vector<float> threshold;
  std::vector<uint32_t> alias;
  std::vector<double> probability;
};
AliasTable buildAliasTable(const std::vector<double>& weights);

}  // namespace tl::lighting
