// Texture images: read under the limits of scene/input_limits.h and decoded by OpenImageIO
// from memory, as PNG or JPEG only (the formats glTF allows), so neither the file's name nor
// its extension can send the bytes to any other of OpenImageIO's decoders.
#include "scene/input_limits.h"
#include "scene/scene_internal.h"

#include <tiny_gltf.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

namespace tl::scene {
namespace {

// Magenta/black 8x8 checker: impossible to miss in a render.
Texture placeholder(const std::string& name) {
  Texture t;
  t.name = name;
  t.width = t.height = 8;
  t.rgba8.resize(8 * 8 * 4);
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) {
      bool on = ((x / 2) + (y / 2)) % 2 == 0;
      uint8_t* p = &t.rgba8[(y * 8 + x) * 4];
      p[0] = on ? 255 : 0, p[1] = 0, p[2] = on ? 255 : 0, p[3] = 255;
    }
  t.placeholder = true;
  return t;
}

// The decoder the bytes themselves call for: PNG and JPEG by their signatures, else none.
const char* formatOf(const std::vector<uint8_t>& bytes) {
  static const uint8_t png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (bytes.size() >= 8 && std::equal(png, png + 8, bytes.begin())) return "png";
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "jpeg";
  return nullptr;
}

}  // namespace

bool decodeImage(const std::vector<uint8_t>& bytes, Texture& t, std::string& error) {
  const char* format = formatOf(bytes);
  if (!format) {
    error = "neither PNG nor JPEG";
    return false;
  }
  OIIO::Filesystem::IOMemReader reader(const_cast<uint8_t*>(bytes.data()), bytes.size());
  OIIO::ImageSpec opened;
  // The proxy is set after create(): OpenImageIO 2.4 drops one given to create() or in the
  // open() configuration for its PNG reader.
  auto in = OIIO::ImageInput::create(format);
  if (!in || !in->set_ioproxy(&reader) || !in->open(std::string("memory.") + format, opened)) {
    error = in ? in->geterror() : OIIO::geterror();
    if (error.empty()) error = fmt::format("not a readable {} image", format);
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  // Checked before anything is allocated for the pixels.
  if (spec.width <= 0 || spec.height <= 0 || uint64_t(spec.width) > InputLimits::kMaxImageSide ||
      uint64_t(spec.height) > InputLimits::kMaxImageSide ||
      uint64_t(spec.width) * uint64_t(spec.height) > InputLimits::kMaxImagePixels) {
    error = fmt::format("{}x{} pixels, more than the {} per side and {} Mpixel allowed", spec.width, spec.height,
                        InputLimits::kMaxImageSide, InputLimits::kMaxImagePixels >> 20);
    return false;
  }
  if (spec.nchannels <= 0 || spec.nchannels > InputLimits::kMaxImageChannels) {
    error = fmt::format("{} channels, not 1 to {}", spec.nchannels, InputLimits::kMaxImageChannels);
    return false;
  }
  const int ch = spec.nchannels;
  std::vector<uint8_t> raw(size_t(spec.width) * spec.height * ch);
  if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::UINT8, raw.data())) {
    error = in->geterror();
    return false;
  }
  t.width = uint32_t(spec.width);
  t.height = uint32_t(spec.height);
  t.rgba8.resize(size_t(t.width) * t.height * 4);
  for (size_t i = 0; i < size_t(t.width) * t.height; ++i) {
    const uint8_t* s = &raw[i * ch];
    uint8_t* d = &t.rgba8[i * 4];
    d[0] = s[0];
    d[1] = ch >= 3 ? s[1] : s[0];
    d[2] = ch >= 3 ? s[2] : s[0];
    d[3] = ch == 2 ? s[1] : ch >= 4 ? s[3] : 255;
  }
  return true;
}

std::optional<uint32_t> TextureCache::get(int textureIndex, bool srgb) {
  if (textureIndex < 0) return std::nullopt;
  if (auto it = cache_.find({textureIndex, srgb}); it != cache_.end()) return it->second;
  std::string name = fmt::format("texture{}", textureIndex);
  Texture t;
  std::string error;
  bool ok = false;
  if (size_t(textureIndex) >= model_.textures.size()) {
    error = "the texture index does not exist";
  } else {
    const auto& tex = model_.textures[size_t(textureIndex)];
    if (tex.source < 0 || size_t(tex.source) >= model_.images.size()) {
      error = "the texture has no valid image";
    } else {
      const auto& img = model_.images[size_t(tex.source)];
      if (!img.name.empty()) name = img.name;
      if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) {
        t.path = referencedPath(file_, img.uri);
        if (img.name.empty()) name = t.path.stem().string();
        try {
          ok = decodeImage(readContained(file_, t.path, options_, InputLimits::kMaxImageFileBytes), t, error);
        } catch (const InputFileError& e) {
          // The message starts with the path, which the warning names already.
          error = e.what();
          if (error.rfind(t.path.string() + ": ", 0) == 0) error = error.substr(t.path.string().size() + 2);
        }
      } else if (!img.image.empty()) {
        // Embedded (bufferView or data URI): decode from memory.
        ok = decodeImage(img.image, t, error);
      } else {
        error = "the image has no data";
      }
    }
  }
  if (!ok) {
    std::string where = t.path.empty() ? name : t.path.string();
    scene_.warnings.push_back(fmt::format("{}: texture {} could not be loaded ({}); using a magenta placeholder",
                                          file_.string(), where, error));
    auto path = t.path;
    t = placeholder(name);
    t.path = path;
  }
  t.name = name;
  t.srgb = srgb;
  t.contentHash = hashTexels(t.width, t.height, t.rgba8);
  uint32_t index = uint32_t(scene_.textures.size());
  scene_.textures.push_back(std::move(t));
  cache_[{textureIndex, srgb}] = index;
  return index;
}

}  // namespace tl::scene
