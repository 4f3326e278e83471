// The glTF importer's pieces, one file per concern, shared between them; not part of the
// scene API. loadGltfBytes (gltf_import.cpp) runs them in order: the file (gltf_file.cpp),
// ignored features (gltf_ignored.cpp), materials (gltf_materials.cpp), meshes
// (gltf_meshes.cpp), skins and the node hierarchy with its instances, cameras and lights
// (gltf_nodes.cpp, gltf_lights.cpp), animations (gltf_animation.cpp), the sun and the sky
// (gltf_lights.cpp). Accessors are read through GltfReader (gltf_reader.h).
#pragma once

#include "scene/gltf_reader.h"
#include "scene/import_values.h"
#include "scene/input_limits.h"
#include "scene/scene_internal.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tl::scene {

// Everything in the file Twinlight does not render (or renders approximately), one entry per
// feature with how often the file uses it: Scene::ignored and one warning each.
class IgnoredFeatures {
 public:
  void add(const std::string& feature, const std::string& instead);
  void report(Scene& scene, const std::filesystem::path& file) const;

 private:
  struct Entry {
    std::string feature, instead;
    size_t count;
  };
  std::vector<Entry> entries_;
};

// What every piece reads and writes: the parsed file, its accessors, the checked values with
// their warnings, the features left out, and the scene being built.
struct GltfImport {
  const tinygltf::Model& model;
  const GltfReader& rd;
  ImportValues& values;
  IgnoredFeatures& ignored;
  Scene& scene;
  const std::filesystem::path& file;
};

// The extensions the importer applies (KHR_materials_emissive_strength, _ior, _specular,
// _unlit, _transmission, _volume, _clearcoat, _pbrSpecularGlossiness (converted), KHR_lights_punctual,
// KHR_mesh_quantization, KHR_texture_transform): a file that requires another is refused, one that merely uses another
// is loaded with an ignored-feature line.
inline bool extensionApplied(const std::string& name) {
  return name == "KHR_materials_emissive_strength" || name == "KHR_materials_ior" || name == "KHR_materials_specular" ||
         name == "KHR_materials_unlit" || name == "KHR_materials_transmission" || name == "KHR_materials_volume" ||
         name == "KHR_materials_clearcoat" || name == "KHR_materials_pbrSpecularGlossiness" ||
         name == "KHR_lights_punctual" || name == "KHR_mesh_quantization" || name == "KHR_texture_transform";
}

// The file's bytes parsed by tinygltf under the input limits (gltf_file.cpp): one SceneError
// for a file too large, nested too deep, not glTF, or requiring an extension not applied.
tinygltf::Model parseGltf(std::vector<uint8_t> bytes, bool binary, const std::filesystem::path& file,
                          const LoadOptions& options);

// Every feature of the file Twinlight does not render, counted (gltf_ignored.cpp).
void scanIgnored(const tinygltf::Model& model, IgnoredFeatures& ignored);

// Scene::materials from the file's materials, their textures through `textures`.
void readMaterials(GltfImport& in, TextureCache& textures);
// A textureInfo inside a material extension (its index, UV set and own extensions; index -1: none).
struct ExtensionTexture {
  int index = -1;
  int texCoord = 0;
  tinygltf::ExtensionMap extensions;
};
ExtensionTexture extensionTexture(const tinygltf::Value& ext, const char* name, ImportValues& values, const std::string& what);
// Reads a material's texture through the importer's cache (srgb: a colour texture).
using TextureReader = std::function<std::optional<TextureRef>(const ExtensionTexture&, bool srgb, const std::string& what)>;
// KHR_materials_ior, _specular, _unlit, _transmission, _volume and _clearcoat into m (gltf_material_extensions.cpp).
void readReflectionExtensions(const tinygltf::Material& gm, Material& m, ImportValues& values, const std::string& what,
                              const TextureReader& texture);
// KHR_materials_pbrSpecularGlossiness converted into m's metal-rough fields, when the material has it.
// The textures' means (scene's textures) stand in for the specular-glossiness texture.
void readSpecularGlossiness(const tinygltf::Material& gm, Material& m, ImportValues& values, const std::string& what,
                            const TextureReader& texture, const Scene& scene);
// The metal-rough material closest to a specular-glossiness one (linear colours), and how far
// glTF's reference shading of it is from the original's (largest difference of F0 and of the
// diffuse colour).
struct SpecularGlossinessConversion {
  glm::vec3 baseColor{0.0f};
  float metallic = 0.0f;
  float error = 0.0f;
};
SpecularGlossinessConversion metalRoughFromSpecularGlossiness(glm::vec3 diffuse, glm::vec3 specular);

// glTF's default material (Lambert 0.8 grey), appended when a primitive names none.
void addDefaultMaterial(Scene& scene);

// Scene::meshes, one per triangle primitive; returns each glTF mesh's primitives (indices into
// Scene::meshes). A primitive without a valid material gets `defaultMaterial`, and `usedDefault`.
std::vector<std::vector<uint32_t>> readMeshes(GltfImport& in, uint32_t defaultMaterial, bool& usedDefault);

// The file's skins (gltf_animation.cpp).
void readSkins(GltfImport& in);
// The default scene's node hierarchy: Scene::nodes, the instances of its meshes, its cameras
// and lights with world transforms (gltf_nodes.cpp). Returns the index of the scene read.
size_t readNodes(GltfImport& in, const std::vector<std::vector<uint32_t>>& meshPrimitives);
// Animations of morph weights and of node translation, rotation and scale, then bounds that
// hold every pose they make (gltf_animation.cpp).
void readAnimations(GltfImport& in);

// One KHR_lights_punctual light at its node's place (gltf_lights.cpp).
std::optional<Light> readLight(const tinygltf::Light& gl, const std::string& nodeName, const glm::dvec3& position,
                               const glm::dquat& orientation, ImportValues& values);
// The sun (the first directional light) and the sky (extras.twinlight.sky_radiance of the file
// or of scene `sceneIndex`) into Scene::environment.
void readEnvironment(GltfImport& in, size_t sceneIndex);

// The texture slots of a material, with their glTF names.
template <class F>
void forEachTextureSlot(const tinygltf::Material& m, F f) {
  f("baseColorTexture", m.pbrMetallicRoughness.baseColorTexture.index, m.pbrMetallicRoughness.baseColorTexture.texCoord,
    m.pbrMetallicRoughness.baseColorTexture.extensions);
  f("metallicRoughnessTexture", m.pbrMetallicRoughness.metallicRoughnessTexture.index,
    m.pbrMetallicRoughness.metallicRoughnessTexture.texCoord, m.pbrMetallicRoughness.metallicRoughnessTexture.extensions);
  f("normalTexture", m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions);
  f("occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord, m.occlusionTexture.extensions);
  f("emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions);
}

// Finite once stored as float, and placing things within InputLimits::kMaxCoordinate.
inline bool usableTransform(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(float(m[c][r]))) return false;
  return std::abs(m[3][0]) <= InputLimits::kMaxCoordinate && std::abs(m[3][1]) <= InputLimits::kMaxCoordinate &&
         std::abs(m[3][2]) <= InputLimits::kMaxCoordinate;
}

// Normals are transformed by the inverse transpose: a singular transform (a zero scale) has
// none, and the float version of it must be finite too.
inline bool invertible(const glm::dmat4& m) {
  const glm::dmat3 l(m);
  const double det = glm::determinant(l);
  if (!std::isfinite(det) || std::abs(det) < 1e-30) return false;
  const glm::mat3 n(glm::transpose(glm::inverse(l)));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(n[c][r])) return false;
  return true;
}

template <int N>
inline bool allFinite(const glm::vec<N, double>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

inline bool withinWorld(const Bounds& b) {
  if (!b.valid()) return true;
  const double most = std::max({std::abs(b.min.x), std::abs(b.min.y), std::abs(b.min.z), std::abs(b.max.x),
                                std::abs(b.max.y), std::abs(b.max.z)});
  return most <= InputLimits::kMaxCoordinate;
}

}  // namespace tl::scene
