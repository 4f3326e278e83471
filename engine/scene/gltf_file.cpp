// The glTF file read and parsed: the file is read here, under the limits of
// scene/input_limits.h (a regular file, its size, its JSON nesting), then tinygltf parses the
// JSON and loads buffers through callbacks that apply the same rules; images are kept as bytes
// and decoded later with OpenImageIO (textures.cpp) so we control missing files.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>
#undef TINYGLTF_IMPLEMENTATION  // the headers below include tiny_gltf.h again: its declarations only

#include "scene/gltf_parts.h"

#include <fmt/format.h>

#include <cstring>

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
// and decode later so a missing texture is a warning, not a failed load. `user` is the model
// being loaded: tinygltf 2.7 hands over an image's bufferView without checking that the view
// lies inside its buffer (fuzz_gltf: a heap-buffer-overflow reading past a 209-byte buffer),
// so the view is checked here before a byte of it is read.
bool keepImageBytes(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* user) {
  const auto& model = *static_cast<const tinygltf::Model*>(user);
  if (image->bufferView >= 0) {
    const auto& views = model.bufferViews;
    const bool viewExists = size_t(image->bufferView) < views.size();
    const auto* view = viewExists ? &views[size_t(image->bufferView)] : nullptr;
    uint64_t end = 0;
    if (!view || view->buffer < 0 || size_t(view->buffer) >= model.buffers.size() ||
        __builtin_add_overflow(uint64_t(view->byteOffset), uint64_t(view->byteLength), &end) ||
        end > model.buffers[size_t(view->buffer)].data.size() || view->byteLength > uint64_t(INT32_MAX)) {
      if (err) *err += fmt::format("image {} refers to bufferView {}, which reaches past the end of its buffer", index,
                                   image->bufferView);
      return false;
    }
  }
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// Buffers named by URI are read through these callbacks under the rules images follow
// (readReferencedFile): no shell expansion, regular files, sizes, the scene's folder.
struct BufferAccess {
  const std::filesystem::path& gltfFile;
  const LoadOptions& options;
  std::string refusal;  // the first buffer refused, and why
};

bool fileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

std::string expandNothing(const std::string& path, void*) { return path; }

bool readBuffer(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& access = *static_cast<BufferAccess*>(user);
  try {
    *out = readContained(access.gltfFile, path, access.options, InputLimits::kMaxFileBytes);
    return true;
  } catch (const InputFileError& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    if (err) *err += e.what();
    return false;
  }
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the importer writes no files";
  return false;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (as much of it as the file holds).
std::string_view jsonText(const std::vector<uint8_t>& bytes, bool binary) {
  const char* text = reinterpret_cast<const char*>(bytes.data());
  if (!binary || bytes.size() < 20) return {text, bytes.size()};
  uint32_t chunkLength = 0;
  std::memcpy(&chunkLength, bytes.data() + 12, 4);
  return {text + 20, std::min<size_t>(chunkLength, bytes.size() - 20)};
}

}  // namespace

Scene loadGltf(const std::filesystem::path& file, const LoadOptions& options) {
  std::string ext = file.extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = ext == ".glb";
  // Read and measured here, before tinygltf allocates anything for it: a device or a FIFO
  // is refused, and JSON nested deeper than the limit never reaches its recursive parser.
  std::vector<uint8_t> bytes;
  try {
    bytes = readRegularFile(file, binary ? InputLimits::kMaxFileBytes : InputLimits::kMaxGltfJsonBytes);
  } catch (const InputFileError& e) {
    throw SceneError(e.what());
  }
  return loadGltfBytes(std::move(bytes), binary, file, options);
}

tinygltf::Model parseGltf(std::vector<uint8_t> bytes, bool binary, const std::filesystem::path& file,
                          const LoadOptions& options) {
  try {
    if (bytes.size() > (binary ? InputLimits::kMaxFileBytes : InputLimits::kMaxGltfJsonBytes))
      throw InputFileError(fmt::format("{}: {} bytes, more than a glTF may have", file.string(), bytes.size()));
    requireJsonDepth(jsonText(bytes, binary), file.string());
  } catch (const InputFileError& e) {
    throw SceneError(e.what());
  }

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  loader.SetImageLoader(keepImageBytes, &model);
  BufferAccess access{file, options, {}};
  loader.SetFsCallbacks({fileExists, expandNothing, readBuffer, writeNothing, &access});
  std::string err, warn;
  const std::string baseDir = file.parent_path().string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                             unsigned(bytes.size()), baseDir);
  } catch (const std::exception& e) {
    throw SceneError(fmt::format("{}: not a valid glTF file ({})", file.string(), oneLine(e.what())));
  }
  if (!ok && !access.refusal.empty())
    throw SceneError(fmt::format("{}: a buffer cannot be read: {}", file.string(), oneLine(access.refusal)));
  if (!ok) throw SceneError(fmt::format("{}: not a valid glTF file: {}", file.string(), oneLine(err.empty() ? warn : err)));
  bytes = {};

  // Extensions the importer applies; a file that *requires* any other is refused rather than
  // shown wrongly (merely *used* extensions are ignored, as the glTF specification allows).
  // KHR_mesh_quantization only widens the attribute types, which the accessor reader decodes
  // (normalized and integer components of every size).
  for (const auto& e : model.extensionsRequired)
    if (!extensionApplied(e)) throw SceneError(fmt::format("{}: requires the unsupported extension {}", file.string(), e));
  return model;
}

}  // namespace tl::scene
