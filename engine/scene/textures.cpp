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

// Reads any OpenImageIO-readable image to RGBA8 (grey -> rgb, missing alpha -> 255).
bool decode(std::unique_ptr<OIIO::ImageInput> in, Texture& t, std::string& error) {
  if (!in) {
    error = OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > 16384 || spec.height > 16384 || spec.nchannels <= 0) {
    error = "unsupported image size";
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

}  // namespace

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
        t.path = file_.parent_path() / img.uri;
        if (!img.name.empty()) name = img.name;
        else name = t.path.stem().string();
        std::error_code ec;
        if (!std::filesystem::exists(t.path, ec)) error = "file not found";
        else ok = decode(OIIO::ImageInput::open(t.path.string()), t, error);
      } else if (!img.image.empty()) {
        // Embedded (bufferView or data URI): decode from memory.
        OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(img.image.data()), img.image.size());
        std::string ext = img.mimeType == "image/jpeg" ? "jpg" : "png";
        OIIO::ImageSpec config;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &reader);
        ok = decode(OIIO::ImageInput::open("embedded." + ext, &config), t, error);
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
