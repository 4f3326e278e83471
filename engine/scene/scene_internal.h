// Pieces of the importer shared between its files; not part of the scene API.
#pragma once

#include "scene/scene.h"

#include <map>
#include <optional>
#include <utility>

namespace tinygltf {
class Model;
}

namespace tl::scene {

// Decodes glTF images with OpenImageIO on first use, once per (texture, colour space).
// A missing or unreadable image becomes a warning and a magenta checker placeholder.
class TextureCache {
 public:
  TextureCache(const tinygltf::Model& model, const std::filesystem::path& gltfFile, Scene& scene)
      : model_(model), file_(gltfFile), scene_(scene) {}
  std::optional<uint32_t> get(int textureIndex, bool srgb);

 private:
  const tinygltf::Model& model_;
  const std::filesystem::path& file_;
  Scene& scene_;
  std::map<std::pair<int, bool>, uint32_t> cache_;
};

// Normals (area-weighted if absent, any degenerate one replaced), tangents (from UVs if
// absent, Gram-Schmidt, handedness in w), all finite and unit length.
void finishVertices(Mesh& mesh, bool haveNormals, bool haveTangents);
Bounds transformBounds(const Bounds& local, const glm::dmat4& transform);

uint64_t hashMesh(const Mesh& mesh);
uint64_t hashMaterial(const Material& material, const std::vector<Texture>& textures);
uint64_t hashScene(const Scene& scene);
uint64_t hashTexels(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8);

}  // namespace tl::scene
