// Node TRS animation on the CPU: every node's world transform at a time, and the scene's
// instances moved to it. Pure; unit-tested against closed forms (tests/unit/test_node_animation.cpp).
#pragma once

#include "scene/scene.h"

#include <vector>

namespace tl::scene {

// `seconds` wrapped into the scene's loop [0, animationSeconds) (unchanged when nothing animates).
double loopedAnimationTime(const Scene& scene, double seconds);

// The keys of an animation channel around time `t`: `lo` the key at or before it, `hi` the one
// after (both the end key outside the keys' range), `f` how far t lies from lo towards hi in
// [0, 1] and `dt` the keys' spacing (0 where lo == hi). Morph-weight and node channels alike.
struct KeySpan {
  size_t lo = 0, hi = 0;
  double f = 0.0, dt = 0.0;
};
KeySpan keySpan(const std::vector<float>& times, double t);

// The node's transform without animation: its matrix, or translation * rotation * scale. The
// importer places the scene with it; nodeLocalTransformAt starts from the same TRS.
glm::dmat4 nodeRestTransform(const Node& node);

// The node's local transform at `seconds`: its TRS with each animated property replaced by its
// channel's value there (LINEAR: lerp, rotations slerped the short way; STEP: the key at or
// before; CUBICSPLINE: the Hermite curve through the keys with their tangents; before the first
// key and after the last: the end keys). A matrix node is never animated.
glm::dmat4 nodeLocalTransformAt(const Scene& scene, uint32_t node, double seconds);

// World (object -> world) transform of every node at `seconds`, parents first.
std::vector<glm::dmat4> nodeWorldTransformsAt(const Scene& scene, double seconds);

// Moves every instance to its node's world transform at `seconds` and updates its world
// bounds; returns how many instances changed transform. Scene::bounds is left as the importer
// made it (every key's pose included), so the scene's size does not change while it plays.
size_t poseInstances(Scene& scene, double seconds);
// The same with the nodes' world transforms already known (nodeWorldTransformsAt).
size_t poseInstances(Scene& scene, const std::vector<glm::dmat4>& nodeWorld);

}  // namespace tl::scene
