// The scene's emissive triangles as the RT path samples them (shared/rt.h RtEmitter): world
// space, chosen in proportion to area x emitted luminance. Pure, tested without a GPU.
#pragma once

#include "scene/scene.h"
#include "shared/rt.h"

#include <glm/glm.hpp>

#include <vector>

namespace tl::lighting {

// Every triangle of every instance whose emission (per instance, rgb) is not black, with its
// cumulative and own selection probability. Empty when nothing emits. Deforming meshes are
// taken in their rest pose.
std::vector<shared::RtEmitter> buildEmitterTable(const scene::Scene& scene, const std::vector<glm::vec3>& instanceEmission);

}  // namespace tl::lighting
