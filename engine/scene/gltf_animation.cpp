// glTF skins and animations: channels of morph weights drive the meshes of their node's
// instances; channels of translation, rotation and scale move nodes (NodeAnimation). Every key
// is checked, and the scene's bounds grow to hold every pose the animations make.
#include "scene/gltf_parts.h"
#include "scene/node_animation.h"
#include "scene/skinning.h"

namespace tl::scene {
namespace {

// An animation sampler's keyframe times: finite and never decreasing, else one error.
std::vector<float> keyTimes(const GltfReader& rd, const tinygltf::AnimationSampler& sampler, size_t animation) {
  std::vector<float> times;
  for (const auto& t : rd.floats<1>(sampler.input, "animation input")) {
    if (!std::isfinite(t.x) || (!times.empty() && t.x < times.back()))
      rd.fail(fmt::format("animation {} has keyframe times that are not finite and increasing", animation));
    times.push_back(t.x);
  }
  return times;
}

// Whether node `root` or a node below it holds a camera or a light (KHR_lights_punctual).
bool holdsCameraOrLight(const tinygltf::Model& model, int root) {
  std::vector<bool> seen(model.nodes.size(), false);
  std::vector<int> open{root};
  while (!open.empty()) {
    const int n = open.back();
    open.pop_back();
    if (n < 0 || size_t(n) >= model.nodes.size() || seen[size_t(n)]) continue;
    seen[size_t(n)] = true;
    const auto& node = model.nodes[size_t(n)];
    if (node.camera >= 0 || node.extensions.count("KHR_lights_punctual")) return true;
    open.insert(open.end(), node.children.begin(), node.children.end());
  }
  return false;
}

// Channels of morph weights: one MorphAnimation per instance of the node they drive.
void readMorphAnimations(GltfImport& in) {
  const tinygltf::Model& model = in.model;
  const GltfReader& rd = in.rd;
  ImportValues& values = in.values;
  Scene& scene = in.scene;
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const auto& anim = model.animations[ai];
    for (const auto& ch : anim.channels) {
      if (ch.target_path != "weights") continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        rd.fail(fmt::format("animation {} has a channel with sampler {}, which does not exist", ai, ch.sampler));
      const auto& sampler = anim.samplers[size_t(ch.sampler)];
      const std::vector<float> times = keyTimes(rd, sampler, ai);
      auto outputs = rd.floats<1>(sampler.output, "animation output");
      const bool cubic = sampler.interpolation == "CUBICSPLINE";
      for (const auto& inst : scene.instances) {
        if (int(inst.node) != ch.target_node || scene.meshes[inst.mesh].morphTargets.empty()) continue;
        const size_t targets = scene.meshes[inst.mesh].morphTargets.size();
        const size_t perKey = cubic ? 3 * targets : targets;
        if (outputs.size() != times.size() * perKey)
          rd.fail(fmt::format("animation {} drives {} morph targets of `{}` with {} values for {} keys", ai, targets,
                              inst.name, outputs.size(), times.size()));
        MorphAnimation a;
        a.mesh = inst.mesh;
        a.step = sampler.interpolation == "STEP";
        a.times = times;
        // A cubic spline's keys hold in-tangents, values and out-tangents: its values, linearly.
        for (size_t k = 0; k < times.size(); ++k)
          for (size_t j = 0; j < targets; ++j) 
            a.weights.push_back(values.morphWeight(outputs[k * perKey + (cubic ? targets : 0) + j].x,
                                                   fmt::format("animation {} weight", ai)));
        if (!a.times.empty()) scene.animationSeconds = std::max(scene.animationSeconds, double(a.times.back()));
        scene.morphAnimations.push_back(std::move(a));
      }
    }
  }
}

// Channels of node translation, rotation and scale (glTF 2.0 section 3.11). Each value is
// checked as the double it is stored in: finite, translations and scales within
// InputLimits::kMaxCoordinate, rotations of non-zero length. Scene::bounds grows to hold the
// instances at every key (and halfway between keys, where a rotation swings furthest from both).
void readNodeAnimations(GltfImport& in) {
  const tinygltf::Model& model = in.model;
  const GltfReader& rd = in.rd;
  ImportValues& values = in.values;
  IgnoredFeatures& ignored = in.ignored;
  Scene& scene = in.scene;
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const auto& anim = model.animations[ai];
    for (const auto& ch : anim.channels) {
      const bool rotation = ch.target_path == "rotation";
      if (ch.target_path != "translation" && !rotation && ch.target_path != "scale") continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        rd.fail(fmt::format("animation {} has a channel with sampler {}, which does not exist", ai, ch.sampler));
      if (ch.target_node < 0) continue;  // glTF: a channel without a node belongs to an extension
      if (size_t(ch.target_node) >= model.nodes.size())
        rd.fail(fmt::format("animation {} drives node {}, which does not exist", ai, ch.target_node));
      const Node& node = scene.nodes[size_t(ch.target_node)];
      if (node.matrix) {
        ignored.add("animation of a node given as a matrix", "not played (glTF animates only nodes given as TRS)");
        continue;
      }
      if (holdsCameraOrLight(model, ch.target_node))
        ignored.add("animation of a camera's or a light's node", "the camera or light stays where the file places it");
      const auto& sampler = anim.samplers[size_t(ch.sampler)];
      NodeAnimation a;
      a.node = uint32_t(ch.target_node);
      a.property = rotation ? NodeProperty::Rotation : ch.target_path == "scale" ? NodeProperty::Scale : NodeProperty::Translation;
      a.interpolation = sampler.interpolation == "STEP"          ? Interpolation::Step
                        : sampler.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                                 : Interpolation::Linear;
      a.times = keyTimes(rd, sampler, ai);
      const size_t perKey = a.interpolation == Interpolation::CubicSpline ? 3 : 1;
      if (rotation) {
        for (const auto& q : rd.floats<4>(sampler.output, "animation output")) a.values.emplace_back(q);
      } else {
        for (const auto& v : rd.floats<3>(sampler.output, "animation output")) a.values.emplace_back(v, 0.0f);
      }
      const std::string what = fmt::format("animation {} {} of node `{}`", ai, ch.target_path, node.name);
      if (a.values.size() != a.times.size() * perKey)
        rd.fail(fmt::format("{} has {} values for {} keys ({} expected)", what, a.values.size(), a.times.size(),
                            a.times.size() * perKey));
      for (size_t k = 0; k < a.values.size(); ++k) {
        const glm::dvec4& v = a.values[k];
        for (int c = 0; c < 4; ++c) values.finite(v[c], what);
        const bool tangent = perKey == 3 && k % 3 != 1;
        if (!rotation && glm::length(glm::dvec3(v)) > InputLimits::kMaxCoordinate)
          rd.fail(fmt::format("{} has a value beyond {:g}", what, InputLimits::kMaxCoordinate));
        if (rotation && !tangent && !(glm::length(v) > 1e-6))
          rd.fail(fmt::format("{} has a rotation of zero length (not a quaternion)", what));
      }
      if (!a.times.empty()) scene.animationSeconds = std::max(scene.animationSeconds, double(a.times.back()));
      scene.nodeAnimations.push_back(std::move(a));
    }
  }
  std::vector<bool> animated(scene.nodes.size(), false);
  for (const auto& a : scene.nodeAnimations) animated[a.node] = true;
  for (const auto& inst : scene.instances) {
    bool moves = false;
    for (int32_t n = int32_t(inst.node); n >= 0 && !moves; n = scene.nodes[size_t(n)].parent) moves = animated[size_t(n)];
    const Material& m = scene.materials[scene.meshes[inst.mesh].material];
    if (moves && (m.emissiveTexture || glm::any(glm::greaterThan(m.emissiveFactor, glm::vec3(0.0f)))))
      ignored.add("an animated emissive mesh", "the rt path samples its light where it rests (the reference and the other paths see it move)");
  }
}

// Bounds that hold every pose the animations make: a skinned mesh's own bounds (object space)
// grow to hold it skinned at each pose, and Scene::bounds to hold every instance at each pose.
// The poses: time 0 and every key of the node channels with the points halfway between (where
// a rotation swings furthest from both), at most kMaxPoses (skinned meshes: kMaxSkinnedPoses,
// each skins every vertex), so a file with many keys costs a bounded import.
void boundAnimatedPoses(const GltfReader& rd, Scene& scene) {
  bool skinned = false;
  for (const auto& m : scene.meshes) skinned |= m.skinned();
  if (scene.nodeAnimations.empty() && !skinned) return;
  std::vector<double> times{0.0};
  for (const auto& a : scene.nodeAnimations) times.insert(times.end(), a.times.begin(), a.times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  auto posesOf = [&](size_t most) {
    std::vector<double> poses;
    const size_t stride = (times.size() + most - 1) / most;
    for (size_t k = 0; k < times.size(); k += stride) {
      poses.push_back(times[k]);
      if (k + stride < times.size()) poses.push_back(0.5 * (times[k] + times[k + stride]));
    }
    return poses;
  };
  constexpr size_t kMaxPoses = 512, kMaxSkinnedPoses = 64;
  if (skinned) {
    // Morph targets move vertices before skinning: pad each mesh by the most any vertex can move
    // (weights in [-1, 1], as morphBounds assumes).
    std::vector<double> morphReach(scene.meshes.size(), 0.0);
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      for (size_t v = 0; v < scene.meshes[m].vertices.size() && scene.meshes[m].skinned(); ++v) {
        double reach = 0.0;
        for (const MorphTarget& target : scene.meshes[m].morphTargets) reach += glm::length(glm::dvec3(target.positions[v]));
        morphReach[m] = std::max(morphReach[m], reach);
      }
    std::vector<Vertex> posed;
    for (double t : posesOf(kMaxSkinnedPoses)) {
      const std::vector<glm::dmat4> world = nodeWorldTransformsAt(scene, t);
      for (const auto& inst : scene.instances) {
        Mesh& mesh = scene.meshes[inst.mesh];
        if (!mesh.skinned()) continue;
        posed = mesh.vertices;
        skinVertices(mesh, jointMatrices(scene.skins[size_t(mesh.skin)], world[inst.node], world), posed);
        const double pad = morphReach[inst.mesh];
        for (const Vertex& v : posed) {
          mesh.bounds.extend(glm::dvec3(v.position) - pad);
          mesh.bounds.extend(glm::dvec3(v.position) + pad);
        }
        if (!withinWorld(mesh.bounds))
          rd.fail(fmt::format("skin `{}` moves mesh `{}` beyond {:g} m", scene.skins[size_t(mesh.skin)].name, mesh.name,
                              InputLimits::kMaxCoordinate));
      }
    }
    // Between the sampled poses a bone swings on an arc that can reach a little past them:
    // 2% of the mesh's size covers the sag of a 16-degree step (1 - cos 8 degrees ~ 1%).
    for (auto& m : scene.meshes)
      if (m.skinned()) {
        const glm::dvec3 margin(0.02 * std::max({m.bounds.size().x, m.bounds.size().y, m.bounds.size().z}));
        m.bounds.min -= margin;
        m.bounds.max += margin;
      }
    for (auto& inst : scene.instances) inst.worldBounds = transformBounds(scene.meshes[inst.mesh].bounds, inst.transform);
  }
  for (double t : posesOf(kMaxPoses)) {
    const std::vector<glm::dmat4> world = nodeWorldTransformsAt(scene, t);
    for (const auto& inst : scene.instances) {
      const Bounds b = transformBounds(scene.meshes[inst.mesh].bounds, world[inst.node]);
      if (!withinWorld(b))
        rd.fail(fmt::format("an animation moves `{}` beyond {:g} m from the origin", inst.name, InputLimits::kMaxCoordinate));
      scene.bounds.extend(b);
    }
  }
}

}  // namespace

// The file's skins: joints (existing nodes) and inverse bind matrices (finite; identity where
// the file gives none, as glTF says).
void readSkins(GltfImport& in) {
  const tinygltf::Model& model = in.model;
  const GltfReader& rd = in.rd;
  Scene& scene = in.scene;
  for (size_t si = 0; si < model.skins.size(); ++si) {
    const auto& gs = model.skins[si];
    Skin skin;
    skin.name = gs.name.empty() ? fmt::format("skin{}", si) : gs.name;
    for (int j : gs.joints) {
      if (j < 0 || size_t(j) >= model.nodes.size())
        rd.fail(fmt::format("skin `{}` has joint node {}, which does not exist", skin.name, j));
      skin.joints.push_back(uint32_t(j));
    }
    skin.inverseBind.assign(skin.joints.size(), glm::dmat4(1.0));
    if (gs.inverseBindMatrices >= 0) {
      const auto matrices = rd.matrices(gs.inverseBindMatrices, "inverseBindMatrices");
      if (matrices.size() < skin.joints.size())
        rd.fail(fmt::format("skin `{}` has {} inverse bind matrices for {} joints", skin.name, matrices.size(), skin.joints.size()));
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        if (!usableTransform(matrices[j]))
          rd.fail(fmt::format("skin `{}` has a non-finite or out-of-range inverse bind matrix (joint {})", skin.name, j));
        skin.inverseBind[j] = matrices[j];
      }
    }
    scene.skins.push_back(std::move(skin));
  }
}

void readAnimations(GltfImport& in) {
  readMorphAnimations(in);
  readNodeAnimations(in);
  boundAnimatedPoses(in.rd, in.scene);
}

}  // namespace tl::scene
