// The glTF node hierarchy: Scene::nodes (their local transforms, for animation), and walked
// from the default scene's roots with world transforms: the instances of each node's mesh (a
// deforming mesh copied per node), its camera and its KHR_lights_punctual light.
#include "scene/gltf_parts.h"
#include "scene/node_animation.h"

#include <glm/gtc/type_ptr.hpp>

#include <functional>

namespace tl::scene {
namespace {

// The node's local transform as animation needs it: TRS, or the matrix a file gives instead.
Node localNode(const tinygltf::Node& n, int index) {
  Node out;
  out.name = n.name.empty() ? fmt::format("node{}", index) : n.name;
  if (n.matrix.size() == 16) out.matrix = glm::make_mat4(n.matrix.data());
  if (n.translation.size() == 3) out.translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
  if (n.rotation.size() == 4) out.rotation = glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) out.scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
  return out;
}

class NodeWalker {
 public:
  NodeWalker(GltfImport& in, const std::vector<std::vector<uint32_t>>& meshPrimitives)
      : in_(in), model_(in.model), rd_(in.rd), values_(in.values), scene_(in.scene), meshPrimitives_(meshPrimitives),
        visited_(model_.nodes.size(), false), meshInstanced_(scene_.meshes.size(), false) {
    for (const auto& m : scene_.meshes) meshDefaultWeights_.push_back(m.morphWeights);
  }

  void visit(int ni, int parentIndex, const glm::dmat4& parent, int depth) {
    if (ni < 0 || size_t(ni) >= model_.nodes.size()) rd_.fail(fmt::format("a node refers to node {}, which does not exist", ni));
    if (visited_[size_t(ni)] || depth > 1000) rd_.fail(fmt::format("node {} appears twice in the hierarchy (a cycle)", ni));
    visited_[size_t(ni)] = true;
    scene_.nodes[size_t(ni)].parent = parentIndex;
    const auto& node = model_.nodes[size_t(ni)];
    glm::dmat4 world = parent * nodeRestTransform(scene_.nodes[size_t(ni)]);
    if (!usableTransform(world))
      rd_.fail(fmt::format("node {} has a non-finite transform or one placing it beyond {:g} m", ni, InputLimits::kMaxCoordinate));
    std::string nodeName = node.name.empty() ? fmt::format("node{}", ni) : node.name;
    if (node.mesh >= 0 && !invertible(world)) {
      // Nothing to see (a zero scale hides a node), and no normal transform to give it.
      values_.warn(fmt::format("node `{}` has a singular transform (a zero scale); its mesh is not drawn", nodeName));
    } else if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model_.meshes.size())
        rd_.fail(fmt::format("node `{}` refers to mesh {}, which does not exist", nodeName, node.mesh));
      addInstances(node, ni, nodeName, world);
    }
    glm::dvec3 position(world[3]);
    glm::dquat orientation = glm::normalize(glm::quat_cast(glm::dmat3(glm::normalize(glm::dvec3(world[0])),
                                                                      glm::normalize(glm::dvec3(world[1])),
                                                                      glm::normalize(glm::dvec3(world[2])))));
    if (node.camera >= 0 && size_t(node.camera) < model_.cameras.size())
      addCamera(model_.cameras[size_t(node.camera)], nodeName, position, orientation);
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
      addLight(it->second, ni, nodeName, position, orientation);
    for (int child : node.children) visit(child, ni, world, depth + 1);
  }

 private:
  // An instance of each primitive of the node's mesh.
  void addInstances(const tinygltf::Node& node, int ni, const std::string& nodeName, const glm::dmat4& world) {
    const GltfReader& rd = rd_;
    Scene& scene = scene_;
    ImportValues& values = values_;
    auto& meshInstanced = meshInstanced_;
    auto& ignored = in_.ignored;
    const auto& prims = meshPrimitives_[size_t(node.mesh)];
    for (size_t k = 0; k < prims.size(); ++k) {
      Instance inst;
      inst.name = prims.size() > 1 ? fmt::format("{}#{}", nodeName, k) : nodeName;
      inst.mesh = prims[k];
      const bool withJoints = !scene.meshes[inst.mesh].joints.empty();
      if (withJoints && node.skin < 0)
        ignored.add("JOINTS_0/WEIGHTS_0 on a node without a skin", "drawn as stored (glTF skins a mesh through its node)");
      if (scene.meshes[inst.mesh].deforms() || (withJoints && node.skin >= 0)) {
        // A deforming mesh follows its node's weights and skin: every further node gets its own copy.
        if (meshInstanced[inst.mesh]) {
          Mesh copy = scene.meshes[inst.mesh];
          copy.name += "@" + nodeName;
          inst.mesh = uint32_t(scene.meshes.size());
          scene.meshes.push_back(std::move(copy));
          meshInstanced.push_back(false);
        }
        Mesh& mesh = scene.meshes[inst.mesh];
        mesh.skin = withJoints ? node.skin : -1;
        if (mesh.skinned()) {
          if (size_t(node.skin) >= scene.skins.size())
            rd.fail(fmt::format("node `{}` refers to skin {}, which does not exist", nodeName, node.skin));
          for (const auto& j : mesh.joints)
            if (std::max({j.x, j.y, j.z, j.w}) >= scene.skins[size_t(node.skin)].joints.size())
              rd.fail(fmt::format("mesh `{}` names joint {} of skin {}, which has {}", mesh.name,
                                  std::max({j.x, j.y, j.z, j.w}), node.skin, scene.skins[size_t(node.skin)].joints.size()));
        }
        // The glTF mesh's own weights, then the node's (an earlier node's never carry over).
        mesh.morphWeights = meshDefaultWeights_[prims[k]];
        for (size_t w = 0; w < node.weights.size() && w < mesh.morphWeights.size(); ++w)
          mesh.morphWeights[w] = values.morphWeight(node.weights[w], fmt::format("node `{}` weight {}", nodeName, w));
      }
      meshInstanced[inst.mesh] = true;
      inst.node = uint32_t(ni);
      inst.transform = world;
      inst.worldBounds = transformBounds(scene.meshes[prims[k]].bounds, world);
      if (!withinWorld(inst.worldBounds))
        rd.fail(fmt::format("node `{}` places mesh `{}` beyond {:g} m from the origin", nodeName,
                            scene.meshes[inst.mesh].name, InputLimits::kMaxCoordinate));
      scene.bounds.extend(inst.worldBounds);
      scene.instances.push_back(std::move(inst));
    }
  }

  void addCamera(const tinygltf::Camera& gc, const std::string& nodeName, const glm::dvec3& position,
                 const glm::dquat& orientation) {
    ImportValues& values = values_;
    Scene& scene = scene_;
    const auto& p = gc.perspective;
    const std::string cameraName = gc.name.empty() ? nodeName : gc.name;
    const auto placed = [&] {  // either kind: the name and where the node puts it
      Camera c;
      c.name = cameraName;
      c.position = position;
      c.orientation = orientation;
      return c;
    };
    // The glTF ranges: 0 < yfov (the session takes up to 178 degrees), 0 < znear < zfar.
    const bool usable = float(p.yfov) > 0.0f && float(p.yfov) < 3.1f && float(p.znear) > 0.0f &&
                        std::isfinite(float(p.znear)) && std::isfinite(float(p.zfar)) &&
                        (p.zfar <= 0.0 || p.zfar > p.znear) && std::isfinite(float(p.aspectRatio)) &&
                        p.aspectRatio >= 0.0 && allFinite(glm::dvec4(orientation.x, orientation.y, orientation.z, orientation.w));
    if (gc.type == "perspective" && !usable) {
      values.warn(fmt::format("camera `{}` has a field of view, clip planes or orientation out of range; it is ignored", cameraName));
    } else if (gc.type == "perspective") {
      Camera c = placed();
      c.yfovRadians = float(p.yfov);
      c.znear = float(p.znear);
      if (p.zfar > 0) c.zfar = float(p.zfar);
      if (p.aspectRatio > 0) c.aspectRatio = float(p.aspectRatio);
      scene.cameras.push_back(c);
    } else if (gc.type == "orthographic") {
      // glTF: xmag and ymag must not be zero (and should not be negative: their size is
      // taken), 0 <= znear < zfar, zfar required.
      const auto& o = gc.orthographic;
      const float xmag = std::abs(float(o.xmag)), ymag = std::abs(float(o.ymag));
      const float znear = float(o.znear), zfar = float(o.zfar);
      const bool orthoUsable = xmag > 0.0f && ymag > 0.0f && std::isfinite(xmag) && std::isfinite(ymag) &&
                               znear >= 0.0f && std::isfinite(zfar) && zfar > znear &&
                               allFinite(glm::dvec4(orientation.x, orientation.y, orientation.z, orientation.w));
      if (!orthoUsable) {
        values.warn(fmt::format("orthographic camera `{}` has a magnification or clip planes out of range; it is ignored",
                                cameraName));
      } else {
        Camera c = placed();
        c.orthographic = true;
        c.xmag = xmag;
        c.ymag = ymag;
        c.znear = znear;
        c.zfar = zfar;
        c.aspectRatio = xmag / ymag;
        scene.cameras.push_back(c);
      }
    }
  }

  void addLight(const tinygltf::Value& extension, int ni, const std::string& nodeName, const glm::dvec3& position,
                const glm::dquat& orientation) {
    const auto& li = extension.Get("light");
    int index = li.IsInt() ? li.GetNumberAsInt() : -1;
    if (index < 0 || size_t(index) >= model_.lights.size())
      values_.fail(fmt::format("node `{}` refers to light {}, which does not exist", nodeName, index));
    if (auto l = readLight(model_.lights[size_t(index)], nodeName, position, orientation, values_)) {
      l->node = uint32_t(ni);
      scene_.lights.push_back(*l);
    }
  }

  GltfImport& in_;
  const tinygltf::Model& model_;
  const GltfReader& rd_;
  ImportValues& values_;
  Scene& scene_;
  const std::vector<std::vector<uint32_t>>& meshPrimitives_;
  std::vector<bool> visited_;
  std::vector<bool> meshInstanced_;
  std::vector<std::vector<float>> meshDefaultWeights_;
};

}  // namespace

size_t readNodes(GltfImport& in, const std::vector<std::vector<uint32_t>>& meshPrimitives) {
  const tinygltf::Model& model = in.model;
  in.scene.nodes.resize(model.nodes.size());
  for (size_t ni = 0; ni < model.nodes.size(); ++ni) in.scene.nodes[ni] = localNode(model.nodes[ni], int(ni));
  NodeWalker walker(in, meshPrimitives);
  std::vector<int> roots;
  const size_t sceneIndex =
      model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? size_t(model.defaultScene) : 0;
  if (!model.scenes.empty()) {
    roots = model.scenes[sceneIndex].nodes;
  } else {
    std::vector<bool> isChild(model.nodes.size(), false);
    for (auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
  }
  for (int r : roots) walker.visit(r, -1, glm::dmat4(1.0), 0);
  return sceneIndex;
}

}  // namespace tl::scene
