// What Twinlight reads from disk, and the limits it reads it under. Every limit is stated
// here, once, and checked before anything is allocated for what it limits: a file's size
// before it is read, a JSON document's nesting before it is parsed, an image's dimensions
// before its pixels are decoded. Files are read only when they are regular files, so a
// device (/dev/zero), a FIFO or a directory named as an input is refused instead of being
// read forever or blocking forever.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tl::scene {

// The limits (docs/user-guide.md, "Input limits").
struct InputLimits {
  // A .gltf document (JSON text) and any file one names (buffers, images), or a .glb.
  static constexpr uint64_t kMaxGltfJsonBytes = uint64_t(256) << 20;
  static constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;  // tinygltf sizes are 32-bit
  // JSON nesting ({ and [) in a glTF document or a settings document. Real glTF files nest
  // about 8 deep; the parser of extras recurses once per level.
  static constexpr size_t kMaxJsonDepth = 64;
  // Decoded images: per side, in pixels overall (RGBA8: 256 MiB) and in channels.
  static constexpr uint32_t kMaxImageSide = 16384;
  static constexpr uint64_t kMaxImagePixels = uint64_t(1) << 26;
  static constexpr int kMaxImageChannels = 4;
  // An image file a glTF names (PNG or JPEG, the formats glTF allows).
  static constexpr uint64_t kMaxImageFileBytes = uint64_t(256) << 20;
  // A settings file (compare --settings).
  static constexpr uint64_t kMaxSettingsBytes = uint64_t(16) << 20;

  // Numbers. Light and emission (radiance, irradiance, intensity, each colour channel after
  // the colour is multiplied by its intensity or strength): 1e10 is six times the sun's
  // disc (1.6e9 cd/m^2) and leaves float headroom for every sum a path forms.
  static constexpr float kMaxLight = 1e10f;
  // World coordinates (m) of geometry, cameras and lights: 1e9 m, a hundred times past the
  // 1e7 m that renders exactly with camera-relative coordinates.
  static constexpr double kMaxCoordinate = 1e9;
  static constexpr float kMaxMorphWeight = 1e3f;
  // Exposure (EV) given by hand.
  static constexpr float kMaxExposureEv = 64.0f;
};

// A file that cannot be used as an input; the message names the file and the reason.
struct InputFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The whole of `file`, which must be a regular file of at most `maxBytes`. Opening never
// blocks (a FIFO is refused, not waited on). Throws InputFileError.
std::vector<uint8_t> readRegularFile(const std::filesystem::path& file, uint64_t maxBytes);

// Throws InputFileError unless `file` is a regular file (or, with `mayBeMissing`, does not
// exist): for inputs another library opens by name (SQLite).
void requireRegularFile(const std::filesystem::path& file, bool mayBeMissing);

// The deepest nesting of objects and arrays in JSON text, counting no further than
// `stopAt` (strings and escapes are skipped; the text need not be valid JSON).
size_t jsonNestingDepth(std::string_view text, size_t stopAt);

// Throws InputFileError when `text` nests deeper than InputLimits::kMaxJsonDepth; `what`
// names the document in the message.
void requireJsonDepth(std::string_view text, const std::string& what);

// Whether `file` lies inside `folder` once both are resolved (symbolic links, `..`).
bool isInsideFolder(const std::filesystem::path& folder, const std::filesystem::path& file);

// "2.0 GiB", "12 MiB", "640 bytes": for messages.
std::string byteSize(uint64_t bytes);

}  // namespace tl::scene
