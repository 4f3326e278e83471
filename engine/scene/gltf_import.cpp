// glTF 2.0 import with tinygltf. tinygltf parses the JSON and loads buffers; images are
// decoded here with OpenImageIO (textures.cpp) so we control missing files. Every
// accessor read is bounds-checked here: tinygltf does not fully validate them, and a
// malformed file must produce one clear error, never a crash.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "scene/morph.h"
#include "scene/scene_internal.h"

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <set>

namespace tl::scene {
namespace {

std::string oneLine(std::string s) {
  for (auto& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  if (s.size() > 300) s = s.substr(0, 300) + "...";
  return s;
}

// tinygltf would otherwise decode images itself; we keep the bytes (for embedded images)
// and decode later so a missing texture is a warning, not a failed load.
bool keepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                    int size, void*) {
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

class Reader {
 public:
  Reader(const tinygltf::Model& m, const std::filesystem::path& file) : m_(m), file_(file) {}

  [[noreturn]] void fail(const std::string& what) const { throw SceneError(fmt::format("{}: {}", file_.string(), what)); }

  // Returns the element pointer, count and stride of an accessor after checking that every
  // element lies inside its buffer.
  struct View {
    const uint8_t* data = nullptr;
    size_t count = 0;
    size_t stride = 0;
    int componentType = 0;
    int type = 0;
    bool normalized = false;
  };

  View accessor(int index, const char* what) const {
    if (index < 0 || size_t(index) >= m_.accessors.size()) fail(fmt::format("{} refers to accessor {}, which does not exist", what, index));
    const auto& a = m_.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(fmt::format("accessor {} ({}) is sparse, which is not supported", index, what));
    View v;
    v.count = a.count;
    v.componentType = a.componentType;
    v.type = a.type;
    v.normalized = a.normalized;
    if (a.bufferView < 0 || size_t(a.bufferView) >= m_.bufferViews.size())
      fail(fmt::format("accessor {} ({}) has no valid bufferView", index, what));
    const auto& bv = m_.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size()) fail(fmt::format("bufferView {} refers to a missing buffer", a.bufferView));
    const auto& buf = m_.buffers[size_t(bv.buffer)].data;
    int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (compSize <= 0 || comps <= 0) fail(fmt::format("accessor {} ({}) has an invalid type", index, what));
    size_t elem = size_t(compSize) * size_t(comps);
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) fail(fmt::format("accessor {} ({}) has a byteStride smaller than its element", index, what));
    size_t begin = bv.byteOffset + a.byteOffset;
    size_t needed = v.count == 0 ? 0 : (v.count - 1) * v.stride + elem;
    if (a.byteOffset + needed > bv.byteLength || begin + needed > buf.size() || bv.byteOffset + bv.byteLength > buf.size())
      fail(fmt::format("accessor {} ({}) reaches past the end of its buffer ({} elements of {} bytes from offset {}, buffer has {} bytes)",
                       index, what, v.count, elem, begin, buf.size()));
    v.data = buf.data() + begin;
    return v;
  }

  float component(const View& v, size_t i, int c) const {
    int size = tinygltf::GetComponentSizeInBytes(uint32_t(v.componentType));
    const uint8_t* p = v.data + i * v.stride + size_t(c) * size_t(size);
    switch (v.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[0] / 255.0f : float(p[0]);
      case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t s; std::memcpy(&s, p, 1); return v.normalized ? std::max(s / 127.0f, -1.0f) : float(s); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); return v.normalized ? u / 65535.0f : float(u); }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t s; std::memcpy(&s, p, 2); return v.normalized ? std::max(s / 32767.0f, -1.0f) : float(s); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); return float(u); }
      default: fail("unsupported accessor component type");
    }
  }

  template <int N>
  std::vector<glm::vec<N, float>> floats(int index, const char* what) const {
    View v = accessor(index, what);
    if (tinygltf::GetNumComponentsInType(uint32_t(v.type)) != N)
      fail(fmt::format("accessor {} ({}) has {} components, expected {}", index, what,
                       tinygltf::GetNumComponentsInType(uint32_t(v.type)), N));
    std::vector<glm::vec<N, float>> out(v.count);
    for (size_t i = 0; i < v.count; ++i)
      for (int c = 0; c < N; ++c) out[i][c] = component(v, i, c);
    return out;
  }

  std::vector<uint32_t> indices(int index) const {
    View v = accessor(index, "indices");
    if (v.type != TINYGLTF_TYPE_SCALAR) fail(fmt::format("index accessor {} is not scalar", index));
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      const uint8_t* p = v.data + i * v.stride;
      switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = p[0]; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); out[i] = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
        default: fail(fmt::format("index accessor {} has a component type indices cannot have", index));
      }
    }
    return out;
  }

 private:
  const tinygltf::Model& m_;
  const std::filesystem::path& file_;
};

glm::dmat4 nodeTransform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 t(1.0);
  if (n.translation.size() == 3) t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  glm::dmat4 r(1.0);
  if (n.rotation.size() == 4) r = glm::mat4_cast(glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  glm::dmat4 s(1.0);
  if (n.scale.size() == 3) s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return t * r * s;
}

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// One KHR_lights_punctual light at its node's place, checked against the extension's
// constraints (a light the file describes wrongly is an error, not a guess).
Light readLight(const tinygltf::Light& gl, const std::string& nodeName, const glm::dvec3& position,
                const glm::dquat& orientation, const Reader& rd) {
  Light l;
  l.name = gl.name.empty() ? nodeName : gl.name;
  if (gl.type == "directional") l.type = LightType::Directional;
  else if (gl.type == "point") l.type = LightType::Point;
  else if (gl.type == "spot") l.type = LightType::Spot;
  else rd.fail(fmt::format("light `{}` has type `{}` (KHR_lights_punctual: directional, point or spot)", l.name, gl.type));
  if (gl.color.size() == 3) l.color = glm::vec3(gl.color[0], gl.color[1], gl.color[2]);
  else if (!gl.color.empty()) rd.fail(fmt::format("light `{}` has a colour of {} numbers (3 expected)", l.name, gl.color.size()));
  l.intensity = float(gl.intensity);
  if (!(l.intensity >= 0.0f) || !std::isfinite(l.intensity) || !(glm::all(glm::greaterThanEqual(l.color, glm::vec3(0.0f)))) ||
      !std::isfinite(l.color.r + l.color.g + l.color.b))
    rd.fail(fmt::format("light `{}` has a negative or non-finite colour or intensity", l.name));
  if (gl.range > 0) l.range = float(gl.range);
  if (l.type == LightType::Spot) {
    l.innerConeAngle = float(gl.spot.innerConeAngle);
    l.outerConeAngle = float(gl.spot.outerConeAngle);
    if (!(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 0.5f * glm::pi<float>() + 1e-6f))
      rd.fail(fmt::format("light `{}` has cone angles inner {} and outer {} (0 <= inner < outer <= pi/2)", l.name,
                          l.innerConeAngle, l.outerConeAngle));
  }
  l.position = position;
  l.direction = glm::normalize(orientation * glm::dvec3(0.0, 0.0, -1.0));
  return l;
}

}  // namespace

Scene loadGltf(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw SceneError(fmt::format("{}: file not found", file.string()));
  if (std::filesystem::is_directory(file, ec)) throw SceneError(fmt::format("{}: is a directory, not a glTF file", file.string()));

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keepImageBytes, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string ext = file.extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  bool ok = false;
  try {
    ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                       : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  } catch (const std::exception& e) {
    throw SceneError(fmt::format("{}: not a valid glTF file ({})", file.string(), oneLine(e.what())));
  }
  if (!ok) throw SceneError(fmt::format("{}: not a valid glTF file: {}", file.string(), oneLine(err.empty() ? warn : err)));

  // Extensions the importer applies; a file that *requires* any other is refused rather than
  // shown wrongly (merely *used* extensions are ignored, as the glTF specification allows).
  static const std::set<std::string> supported = {"KHR_materials_emissive_strength", "KHR_lights_punctual"};
  for (const auto& e : model.extensionsRequired)
    if (!supported.count(e)) throw SceneError(fmt::format("{}: requires the unsupported extension {}", file.string(), e));

  Reader rd(model, file);
  Scene scene;
  scene.name = file.stem().string();
  scene.path = file;

  // Textures: one entry per (glTF texture, colour space) actually used by a material.
  TextureCache textures(model, file, scene);

  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& gm = model.materials[i];
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name.empty() ? fmt::format("material{}", i) : gm.name;
    if (pbr.baseColorFactor.size() == 4)
      m.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    if (gm.emissiveFactor.size() == 3) m.emissiveFactor = glm::vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end()) {
      const auto& s = it->second.Get("emissiveStrength");
      if (s.IsNumber()) m.emissiveStrength = float(s.GetNumberAsDouble());
    }
    m.normalScale = float(gm.normalTexture.scale);
    m.alphaMode = gm.alphaMode == "MASK" ? AlphaMode::Mask : gm.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alphaCutoff = float(gm.alphaCutoff);
    m.doubleSided = gm.doubleSided;
    m.baseColorTexture = textures.get(pbr.baseColorTexture.index, true);
    m.metallicRoughnessTexture = textures.get(pbr.metallicRoughnessTexture.index, false);
    m.normalTexture = textures.get(gm.normalTexture.index, false);
    m.emissiveTexture = textures.get(gm.emissiveTexture.index, true);
    scene.materials.push_back(std::move(m));
  }
  const uint32_t defaultMaterial = uint32_t(scene.materials.size());
  bool usedDefault = false;

  // Meshes: one per primitive.
  std::vector<std::vector<uint32_t>> meshPrimitives(model.meshes.size());
  for (size_t mi = 0; mi < model.meshes.size(); ++mi) {
    const auto& gmesh = model.meshes[mi];
    for (size_t pi = 0; pi < gmesh.primitives.size(); ++pi) {
      const auto& prim = gmesh.primitives[pi];
      std::string name = gmesh.name.empty() ? fmt::format("mesh{}", mi) : gmesh.name;
      if (pi > 0) name += fmt::format("#{}", pi);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
        scene.warnings.push_back(fmt::format("{}: mesh `{}` primitive {} is not triangles (mode {}); skipped",
                                             file.string(), name, pi, prim.mode));
        continue;
      }
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) rd.fail(fmt::format("mesh `{}` primitive {} has no POSITION", name, pi));
      Mesh mesh;
      mesh.name = name;
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

      bool haveNormals = false;
      if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        auto normals = rd.floats<3>(it->second, "NORMAL");
        if (normals.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} normals for {} vertices", name, normals.size(), mesh.vertices.size()));
        for (size_t v = 0; v < normals.size(); ++v) mesh.vertices[v].normal = normals[v];
        haveNormals = true;
      }
      if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        auto uvs = rd.floats<2>(it->second, "TEXCOORD_0");
        if (uvs.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} UVs for {} vertices", name, uvs.size(), mesh.vertices.size()));
        for (size_t v = 0; v < uvs.size(); ++v) mesh.vertices[v].uv = uvs[v];
      }
      bool haveTangents = false;
      if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
        auto tangents = rd.floats<4>(it->second, "TANGENT");
        if (tangents.size() == mesh.vertices.size()) {
          for (size_t v = 0; v < tangents.size(); ++v) mesh.vertices[v].tangent = tangents[v];
          haveTangents = true;
        }
      }
      finishVertices(mesh, haveNormals, haveTangents);
      // Morph targets: displacements of positions (and normals) added with weights.
      for (size_t ti = 0; ti < prim.targets.size(); ++ti) {
        MorphTarget target;
        target.positions.assign(mesh.vertices.size(), glm::vec3(0.0f));
        for (const auto& [attribute, index] : prim.targets[ti]) {
          if (attribute != "POSITION" && attribute != "NORMAL") continue;  // tangent deltas are not applied
          auto deltas = rd.floats<3>(index, "morph target");
          if (deltas.size() != mesh.vertices.size())
            rd.fail(fmt::format("mesh `{}` morph target {} has {} {} deltas for {} vertices", name, ti, deltas.size(),
                                attribute, mesh.vertices.size()));
          for (const auto& d : deltas)
            if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z))
              rd.fail(fmt::format("mesh `{}` morph target {} has a non-finite {} delta", name, ti, attribute));
          (attribute == "POSITION" ? target.positions : target.normals) = std::move(deltas);
        }
        mesh.morphTargets.push_back(std::move(target));
      }
      if (!mesh.morphTargets.empty()) {
        mesh.morphWeights.assign(mesh.morphTargets.size(), 0.0f);
        for (size_t k = 0; k < gmesh.weights.size() && k < mesh.morphWeights.size(); ++k)
          mesh.morphWeights[k] = float(gmesh.weights[k]);
        mesh.bounds = morphBounds(mesh);
      }
      if (prim.material >= 0 && size_t(prim.material) < scene.materials.size()) {
        mesh.material = uint32_t(prim.material);
      } else {
        mesh.material = defaultMaterial;
        usedDefault = true;
      }
      mesh.contentHash = hashMesh(mesh);
      meshPrimitives[mi].push_back(uint32_t(scene.meshes.size()));
      scene.meshes.push_back(std::move(mesh));
    }
  }
  if (usedDefault || scene.materials.empty()) {
    Material m;
    m.name = "default";
    m.metallic = 0.0f;
    m.roughness = 0.8f;
    m.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    scene.materials.push_back(m);
  }
  for (auto& m : scene.materials) m.contentHash = hashMaterial(m, scene.textures);

  // Node hierarchy -> instances, cameras and lights with world transforms.
  std::vector<bool> meshInstanced(scene.meshes.size(), false);
  std::vector<std::vector<float>> meshDefaultWeights;
  for (const auto& m : scene.meshes) meshDefaultWeights.push_back(m.morphWeights);
  std::vector<bool> visited(model.nodes.size(), false);
  std::function<void(int, const glm::dmat4&, int)> visit = [&](int ni, const glm::dmat4& parent, int depth) {
    if (ni < 0 || size_t(ni) >= model.nodes.size()) rd.fail(fmt::format("a node refers to node {}, which does not exist", ni));
    if (visited[size_t(ni)] || depth > 1000) rd.fail(fmt::format("node {} appears twice in the hierarchy (a cycle)", ni));
    visited[size_t(ni)] = true;
    const auto& node = model.nodes[size_t(ni)];
    glm::dmat4 world = parent * nodeTransform(node);
    if (!finite(world)) rd.fail(fmt::format("node {} has a non-finite transform", ni));
    std::string nodeName = node.name.empty() ? fmt::format("node{}", ni) : node.name;
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model.meshes.size()) rd.fail(fmt::format("node `{}` refers to mesh {}, which does not exist", nodeName, node.mesh));
      const auto& prims = meshPrimitives[size_t(node.mesh)];
      for (size_t k = 0; k < prims.size(); ++k) {
        Instance inst;
        inst.name = prims.size() > 1 ? fmt::format("{}#{}", nodeName, k) : nodeName;
        inst.mesh = prims[k];
        if (scene.meshes[inst.mesh].deforms()) {
          // A deforming mesh follows its node's weights: every further node gets its own copy.
          if (meshInstanced[inst.mesh]) {
            Mesh copy = scene.meshes[inst.mesh];
            copy.name += "@" + nodeName;
            inst.mesh = uint32_t(scene.meshes.size());
            scene.meshes.push_back(std::move(copy));
            meshInstanced.push_back(false);
          }
          // The glTF mesh's own weights, then the node's (an earlier node's never carry over).
          Mesh& mesh = scene.meshes[inst.mesh];
          mesh.morphWeights = meshDefaultWeights[prims[k]];
          for (size_t w = 0; w < node.weights.size() && w < mesh.morphWeights.size(); ++w)
            mesh.morphWeights[w] = float(node.weights[w]);
        }
        meshInstanced[inst.mesh] = true;
        inst.node = uint32_t(ni);
        inst.transform = world;
        inst.worldBounds = transformBounds(scene.meshes[prims[k]].bounds, world);
        scene.bounds.extend(inst.worldBounds);
        scene.instances.push_back(std::move(inst));
      }
    }
    glm::dvec3 position(world[3]);
    glm::dquat orientation = glm::normalize(glm::quat_cast(glm::dmat3(glm::normalize(glm::dvec3(world[0])),
                                                                      glm::normalize(glm::dvec3(world[1])),
                                                                      glm::normalize(glm::dvec3(world[2])))));
    if (node.camera >= 0 && size_t(node.camera) < model.cameras.size()) {
      const auto& gc = model.cameras[size_t(node.camera)];
      if (gc.type == "perspective") {
        Camera c;
        c.name = gc.name.empty() ? nodeName : gc.name;
        c.position = position;
        c.orientation = orientation;
        c.yfovRadians = float(gc.perspective.yfov);
        c.znear = float(gc.perspective.znear);
        if (gc.perspective.zfar > 0) c.zfar = float(gc.perspective.zfar);
        if (gc.perspective.aspectRatio > 0) c.aspectRatio = float(gc.perspective.aspectRatio);
        scene.cameras.push_back(c);
      }
    }
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const auto& li = it->second.Get("light");
      int index = li.IsInt() ? li.GetNumberAsInt() : -1;
      if (index < 0 || size_t(index) >= model.lights.size())
        rd.fail(fmt::format("node `{}` refers to light {}, which does not exist", nodeName, index));
      scene.lights.push_back(readLight(model.lights[size_t(index)], nodeName, position, orientation, rd));
    }
    for (int child : node.children) visit(child, world, depth + 1);
  };
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
  for (int r : roots) visit(r, glm::dmat4(1.0), 0);

  // Animations: channels of morph weights drive the meshes of their node's instances. Node
  // transforms are not animated (a warning says so once per file).
  bool warnedTransforms = false;
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const auto& anim = model.animations[ai];
    for (const auto& ch : anim.channels) {
      if (ch.target_path != "weights") {
        if (!warnedTransforms)
          scene.warnings.push_back(fmt::format("{}: node {} animations are not played (only morph weights are)",
                                               file.string(), ch.target_path));
        warnedTransforms = true;
        continue;
      }
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        rd.fail(fmt::format("animation {} has a channel with sampler {}, which does not exist", ai, ch.sampler));
      const auto& sampler = anim.samplers[size_t(ch.sampler)];
      auto times = rd.floats<1>(sampler.input, "animation input");
      auto values = rd.floats<1>(sampler.output, "animation output");
      for (size_t k = 0; k < times.size(); ++k)
        if (!std::isfinite(times[k].x) || (k > 0 && times[k].x < times[k - 1].x))
          rd.fail(fmt::format("animation {} has keyframe times that are not finite and increasing", ai));
      const bool cubic = sampler.interpolation == "CUBICSPLINE";
      for (const auto& inst : scene.instances) {
        if (int(inst.node) != ch.target_node || !scene.meshes[inst.mesh].deforms()) continue;
        const size_t targets = scene.meshes[inst.mesh].morphTargets.size();
        const size_t perKey = cubic ? 3 * targets : targets;
        if (values.size() != times.size() * perKey)
          rd.fail(fmt::format("animation {} drives {} morph targets of `{}` with {} values for {} keys", ai, targets,
                              inst.name, values.size(), times.size()));
        MorphAnimation a;
        a.mesh = inst.mesh;
        a.step = sampler.interpolation == "STEP";
        for (const auto& t : times) a.times.push_back(t.x);
        // A cubic spline's keys hold in-tangents, values and out-tangents: its values, linearly.
        for (size_t k = 0; k < times.size(); ++k)
          for (size_t j = 0; j < targets; ++j) a.weights.push_back(values[k * perKey + (cubic ? targets : 0) + j].x);
        if (!a.times.empty()) scene.animationSeconds = std::max(scene.animationSeconds, double(a.times.back()));
        scene.morphAnimations.push_back(std::move(a));
      }
    }
  }

  // Environment: the first directional light is the sun; the others are shaded from the light table.
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.type != LightType::Directional) continue;
    scene.environment.sunDirection = l.direction;
    scene.environment.sunIrradiance = l.radiometric();
    scene.environment.sunFromFile = true;
    scene.environment.sunLight = i;
    break;
  }
  auto readSky = [&](const tinygltf::Value& extras) {
    if (!extras.IsObject() || !extras.Has("twinlight")) return;
    const auto& t = extras.Get("twinlight");
    const auto& sky = t.Get("sky_radiance");
    if (sky.IsArray() && sky.ArrayLen() == 3) {
      glm::vec3 c;
      for (int k = 0; k < 3; ++k) {
        const auto& v = sky.Get(k);
        if (!v.IsNumber() || v.GetNumberAsDouble() < 0.0) rd.fail("extras.twinlight.sky_radiance must be three non-negative numbers");
        c[k] = float(v.GetNumberAsDouble());
      }
      scene.environment.skyRadiance = c;
    }
  };
  readSky(model.extras);
  if (!model.scenes.empty()) readSky(model.scenes[sceneIndex].extras);

  scene.contentHash = hashScene(scene);
  return scene;
}

}  // namespace tl::scene
