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
  TextureCache(const tinygltf::Model& model, const std::filesystem::path& gltfFile, const LoadOptions& options, Scene& scene)
      : model_(model), file_(gltfFile), options_(options), scene_(scene) {}
  std::optional<uint32_t> get(int textureIndex, bool srgb);

 private:
  const tinygltf::Model& model_;
  const std::filesystem::path& file_;
  const LoadOptions& options_;
  Scene& scene_;
  std::map<std::pair<int, bool>, uint32_t> cache_;
};

// loadGltf after reading the file: `bytes` are its contents (a .glb when `binary`); files it
// names resolve next to `file`. The fuzz target (fuzz/fuzz_gltf.cpp) enters here.
Scene loadGltfBytes(std::vector<uint8_t> bytes, bool binary, const std::filesystem::path& file, const LoadOptions& options);

// A file the glTF `gltfFile` names by `uri` (percent-encoded, relative to the glTF's folder),
// read under `maxBytes`; throws InputFileError naming the reason (missing, not a regular file,
// too large, outside the folder unless options allow it).
std::vector<uint8_t> readReferencedFile(const std::filesystem::path& gltfFile, const std::string& uri,
                                        const LoadOptions& options, uint64_t maxBytes);
// Where that file is (no check).
std::filesystem::path referencedPath(const std::filesystem::path& gltfFile, const std::string& uri);
// `path` (already resolved) read under the same rules.
std::vector<uint8_t> readContained(const std::filesystem::path& gltfFile, const std::filesystem::path& path,
                                   const LoadOptions& options, uint64_t maxBytes);

// Decodes PNG or JPEG bytes into `t` (RGBA8, grey -> rgb, missing alpha -> 255) under the
// image limits of scene/input_limits.h; false with `error` for anything else.
bool decodeImage(const std::vector<uint8_t>& bytes, Texture& t, std::string& error);

// Normals (area-weighted if absent, any degenerate one replaced), tangents (from UVs if
// absent, Gram-Schmidt, handedness in w), all finite and unit length.
void finishVertices(Mesh& mesh, bool haveNormals, bool haveTangents);
Bounds transformBounds(const Bounds& local, const glm::dmat4& transform);

uint64_t hashMesh(const Mesh& mesh);
uint64_t hashMaterial(const Material& material, const std::vector<Texture>& textures);
uint64_t hashScene(const Scene& scene);
uint64_t hashTexels(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8);

}  // namespace tl::scene
