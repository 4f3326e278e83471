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

// The sampler glTF texture `samplerIndex` names (-1: none, glTF's defaults).
SamplerMode samplerMode(const tinygltf::Model& model, int samplerIndex);

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

// Decodes PNG, JPEG, OpenEXR or Radiance HDR bytes (the decoder chosen by their signature,
// never by a name) into `t` at the precision its bit depth needs (scene.h TexelFormat; `t.srgb`
// must be set: 16-bit colour is decoded from sRGB here), grey -> rgb, missing alpha -> one,
// under the image limits of scene/input_limits.h; false with `error` for anything else.
bool decodeImage(const std::vector<uint8_t>& bytes, Texture& t, std::string& error);
// A JPEG's bytes without the metadata segments a texture never uses (APP1-APP13, APP15 and
// comments: EXIF, XMP, ICC, Photoshop/IPTC): OpenImageIO 2.4 parses them on open() and its IPTC
// reader reads past the end of an APP13 segment (heap-buffer-overflow found by fuzz_image).
// APP0 (JFIF) and APP14 (Adobe colour transform) stay: libjpeg decodes by them. Markers are
// found the way libjpeg finds them (garbage between segments skipped, lengths below 2 read
// as empty), so that no segment libjpeg would hand to OpenImageIO is left in.
std::vector<uint8_t> jpegWithoutMetadata(const std::vector<uint8_t>& bytes);

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
