// Files a glTF names: buffers and images, by URI relative to the glTF's folder. Unless the
// load options allow it, they must lie inside that folder once `..` and symbolic links are
// resolved: a scene from elsewhere reads its own files, not ../../../../etc/passwd.
#include "scene/input_limits.h"
#include "scene/scene_internal.h"

#include <fmt/format.h>

namespace tl::scene {
namespace {

std::filesystem::path folderOf(const std::filesystem::path& gltfFile) {
  return gltfFile.has_parent_path() ? gltfFile.parent_path() : std::filesystem::path(".");
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// RFC 3986 percent-decoding (glTF URIs are URI references: "my%20texture.png").
std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hexDigit(uri[i + 1]) >= 0 && hexDigit(uri[i + 2]) >= 0) {
      out += char(hexDigit(uri[i + 1]) * 16 + hexDigit(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::filesystem::path referencedPath(const std::filesystem::path& gltfFile, const std::string& uri) {
  return folderOf(gltfFile) / percentDecoded(uri);
}

std::vector<uint8_t> readContained(const std::filesystem::path& gltfFile, const std::filesystem::path& path,
                                   const LoadOptions& options, uint64_t maxBytes) {
  if (!options.allowOutsideFolder && !isInsideFolder(folderOf(gltfFile), path))
    throw InputFileError(fmt::format("{}: lies outside the folder of {} (files outside it are read only when allowed: "
                                     "--allow-outside-files)",
                                     path.string(), gltfFile.filename().string()));
  return readRegularFile(path, maxBytes);
}

std::vector<uint8_t> readReferencedFile(const std::filesystem::path& gltfFile, const std::string& uri,
                                        const LoadOptions& options, uint64_t maxBytes) {
  return readContained(gltfFile, referencedPath(gltfFile, uri), options, maxBytes);
}

}  // namespace tl::scene
