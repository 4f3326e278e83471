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

// Decodes glTF images with OpenImageIO on first use, once per (texture, colour space), from
// any source glTF allows: a file next to the .gltf, a data: URI or a .glb bufferView (the
// last two from memory). One decoder for every source and bit depth: tinygltf's stb_image
// would cover 8/16-bit PNG and JPEG but not EXR/HDR, which OpenImageIO reads as well.
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

// Normals (area-weighted if absent, any degenerate one replaced) and tangents (supplied ones
// as given, else generated the MikkTSpace way: mesh_processing.cpp), all finite and unit
// length, handedness in w. Generating may split vertices where a UV mirror seam gives one
// vertex both handednesses: returns, per vertex, the index it was copied from (identity for
// the ones that were there), which per-vertex data read later (morph targets) follows.
std::vector<uint32_t> finishVertices(Mesh& mesh, bool haveNormals, bool haveTangents);
Bounds transformBounds(const Bounds& local, const glm::dmat4& transform);

uint64_t hashMesh(const Mesh& mesh);
uint64_t hashMaterial(const Material& material, const std::vector<Texture>& textures);
uint64_t hashScene(const Scene& scene);
uint64_t hashTexels(const Texture& texture);

}  // namespace tl::scene
