#include "scene/node_animation.h"

#include "scene/scene_internal.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace tl::scene {
namespace {

glm::dquat asQuat(const glm::dvec4& v) { return glm::dquat(v.w, v.x, v.y, v.z); }

// The channel's value at t (xyz, or a quaternion as xyzw), normalised for rotations.
glm::dvec4 channelValue(const NodeAnimation& a, double t) {
  const KeySpan k = keySpan(a.times, t);
  const bool cubic = a.interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t key) { return a.values[cubic ? 3 * key + 1 : key]; };
  glm::dvec4 v;
  if (k.hi == k.lo || a.interpolation == Interpolation::Step) {
    v = value(k.lo);
  } else if (cubic) {
    // glTF's cubic Hermite spline: tangents are per second, scaled by the keys' spacing.
    const double s = k.f, s2 = s * s, s3 = s2 * s;
    const glm::dvec4 p0 = value(k.lo), p1 = value(k.hi);
    const glm::dvec4 m0 = k.dt * a.values[3 * k.lo + 2], m1 = k.dt * a.values[3 * k.hi];
    v = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
  } else if (a.property == NodeProperty::Rotation) {
    const glm::dquat q = glm::slerp(asQuat(value(k.lo)), asQuat(value(k.hi)), k.f);  // glm takes the short way
    v = glm::dvec4(q.x, q.y, q.z, q.w);
  } else {
    v = value(k.lo) + k.f * (value(k.hi) - value(k.lo));
  }
  if (a.property == NodeProperty::Rotation) {
    const double len = glm::length(v);
    v = len > 1e-12 ? v / len : glm::dvec4(0.0, 0.0, 0.0, 1.0);
  }
  return v;
}

}  // namespace

KeySpan keySpan(const std::vector<float>& times, double t) {
  KeySpan s;
  const auto next = std::upper_bound(times.begin(), times.end(), float(t));
  s.hi = size_t(std::min<ptrdiff_t>(next - times.begin(), ptrdiff_t(times.size()) - 1));
  s.lo = next == times.begin() ? 0 : size_t(next - times.begin()) - 1;
  if (s.hi > s.lo) {
    s.dt = double(times[s.hi]) - double(times[s.lo]);
    s.f = std::clamp((t - double(times[s.lo])) / std::max(1e-9, s.dt), 0.0, 1.0);
  }
  return s;
}

double loopedAnimationTime(const Scene& scene, double seconds) {
  if (!(scene.animationSeconds > 0.0)) return seconds;
  double t = std::fmod(seconds, scene.animationSeconds);
  return t < 0.0 ? t + scene.animationSeconds : t;
}

namespace {

glm::dmat4 trs(const glm::dvec3& translation, const glm::dquat& rotation, const glm::dvec3& scale) {
  return glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) * glm::scale(glm::dmat4(1.0), scale);
}

// The node's local transform at looped time t under `channels` (its own).
glm::dmat4 localTransform(const Node& n, const std::vector<const NodeAnimation*>& channels, double t) {
  if (n.matrix) return *n.matrix;
  glm::dvec3 translation = n.translation, scale = n.scale;
  glm::dquat rotation = n.rotation;
  for (const NodeAnimation* a : channels) {
    if (a->times.empty()) continue;
    const glm::dvec4 v = channelValue(*a, t);
    switch (a->property) {
      case NodeProperty::Translation: translation = glm::dvec3(v); break;
      case NodeProperty::Rotation: rotation = asQuat(v); break;
      case NodeProperty::Scale: scale = glm::dvec3(v); break;
    }
  }
  return trs(translation, rotation, scale);
}

std::vector<std::vector<const NodeAnimation*>> channelsByNode(const Scene& scene) {
  std::vector<std::vector<const NodeAnimation*>> byNode(scene.nodes.size());
  for (const NodeAnimation& a : scene.nodeAnimations)
    if (a.node < byNode.size()) byNode[a.node].push_back(&a);
  return byNode;
}

}  // namespace

glm::dmat4 nodeRestTransform(const Node& node) { return node.matrix ? *node.matrix : trs(node.translation, node.rotation, node.scale); }

glm::dmat4 nodeLocalTransformAt(const Scene& scene, uint32_t node, double seconds) {
  return localTransform(scene.nodes.at(node), channelsByNode(scene).at(node), loopedAnimationTime(scene, seconds));
}

std::vector<glm::dmat4> nodeWorldTransformsAt(const Scene& scene, double seconds) {
  const auto channels = channelsByNode(scene);
  const double t = loopedAnimationTime(scene, seconds);
  std::vector<glm::dmat4> world(scene.nodes.size(), glm::dmat4(1.0));
  std::vector<uint8_t> done(scene.nodes.size(), 0);
  // The importer refuses cycles, so following parents ends; a chain is resolved root first.
  std::vector<uint32_t> chain;
  for (uint32_t i = 0; i < scene.nodes.size(); ++i) {
    chain.clear();
    for (int32_t n = int32_t(i); n >= 0 && !done[size_t(n)]; n = scene.nodes[size_t(n)].parent) chain.push_back(uint32_t(n));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int32_t parent = scene.nodes[*it].parent;
      const glm::dmat4 local = localTransform(scene.nodes[*it], channels[*it], t);
      world[*it] = parent >= 0 ? world[size_t(parent)] * local : local;
      done[*it] = 1;
    }
  }
  return world;
}

size_t poseInstances(Scene& scene, double seconds) {
  if (scene.nodeAnimations.empty()) return 0;
  return poseInstances(scene, nodeWorldTransformsAt(scene, seconds));
}

size_t poseInstances(Scene& scene, const std::vector<glm::dmat4>& world) {
  size_t moved = 0;
  for (Instance& inst : scene.instances) {
    if (inst.node >= world.size() || world[inst.node] == inst.transform) continue;
    inst.transform = world[inst.node];
    inst.worldBounds = transformBounds(scene.meshes[inst.mesh].bounds, inst.transform);
    ++moved;
  }
  return moved;
}

}  // namespace tl::scene
