#include "scene/scene_internal.h"

#include "shared/color.h"

#include <tiny_gltf.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include <cstring>

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

// Channel c (0..3) of an RGBA texel from `ch` stored channels: grey -> rgb, missing alpha -> one.
template <class T>
T expand(const T* s, int ch, int c, T one) {
  if (c < 3) return ch >= 3 ? s[c] : s[0];
  return ch == 2 ? s[1] : ch >= 4 ? s[3] : one;
}

// Reads any OpenImageIO-readable image into the texel format its bit depth needs:
// 8-bit stays 8-bit; 16-bit becomes Rgba16Unorm (linear data) or, for colour (`srgb`), linear
// half floats; float images become half floats as they are (already linear).
bool decode(std::unique_ptr<OIIO::ImageInput> in, Texture& t, std::string& error) {
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = "no decoder reads it";
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > 16384 || spec.height > 16384 || spec.nchannels <= 0) {
    error = "unsupported image size";
    return false;
  }
  const int ch = spec.nchannels;
  const size_t texels = size_t(spec.width) * size_t(spec.height);
  t.width = uint32_t(spec.width);
  t.height = uint32_t(spec.height);
  t.fileFormat = in->format_name();
  const OIIO::TypeDesc::BASETYPE base = OIIO::TypeDesc::BASETYPE(spec.format.basetype);
  const bool isFloat = base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::DOUBLE;
  const bool deep = spec.format.size() > 1 && !isFloat;
  t.fileBits = isFloat ? int(spec.format.size()) * 8 : deep ? 16 : 8;

  if (!isFloat && !deep) {
    std::vector<uint8_t> raw(texels * size_t(ch));
    if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::UINT8, raw.data())) {
      error = in->geterror();
      return false;
    }
    t.format = TexelFormat::Rgba8;
    t.rgba8.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i)
      for (int c = 0; c < 4; ++c) t.rgba8[i * 4 + size_t(c)] = expand<uint8_t>(&raw[i * size_t(ch)], ch, c, 255);
    return true;
  }
  if (deep && !t.srgb) {
    std::vector<uint16_t> raw(texels * size_t(ch));
    if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::UINT16, raw.data())) {
      error = in->geterror();
      return false;
    }
    t.format = TexelFormat::Rgba16Unorm;
    t.rgba16.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i)
      for (int c = 0; c < 4; ++c) t.rgba16[i * 4 + size_t(c)] = expand<uint16_t>(&raw[i * size_t(ch)], ch, c, 65535);
    return true;
  }
  // Float images, and 16-bit colour decoded from sRGB here (alpha stays linear).
  std::vector<float> raw(texels * size_t(ch));
  if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::FLOAT, raw.data())) {
    error = in->geterror();
    return false;
  }
  t.format = TexelFormat::Rgba16Float;
  t.rgba16.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    glm::vec4 v;
    for (int c = 0; c < 4; ++c) v[c] = expand<float>(&raw[i * size_t(ch)], ch, c, 1.0f);
    if (!isFloat) v = glm::vec4(shared::tlSrgbToLinear(glm::vec3(v)), v.a);
    for (int c = 0; c < 4; ++c) {
      // Half floats top out at 65504; a larger or non-finite texel would poison every filter tap.
      const float x = std::isfinite(v[c]) ? glm::clamp(v[c], -65504.0f, 65504.0f) : 0.0f;
      t.rgba16[i * 4 + size_t(c)] = glm::packHalf1x16(x);
    }
  }
  return true;
}

// The file extension OpenImageIO should pick its decoder by, from the image's first bytes
// (a glTF mimeType may be absent or wrong; the bytes are not).
std::string sniffExtension(const std::vector<unsigned char>& bytes, const std::string& mimeType) {
  auto starts = [&](const char* magic, size_t n) { return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0; };
  if (starts("\x89PNG", 4)) return "png";
  if (starts("\xFF\xD8\xFF", 3)) return "jpg";
  if (starts("\x76\x2F\x31\x01", 4)) return "exr";
  if (starts("#?RADIANCE", 10) || starts("#?RGBE", 6)) return "hdr";
  return mimeType == "image/jpeg" ? "jpg" : "png";
}

std::string oneLineError(std::string s) {
  for (auto& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

glm::vec4 texelValue(const Texture& t, size_t i) {
  switch (t.format) {
    case TexelFormat::Rgba8:
      return glm::vec4(t.rgba8[4 * i], t.rgba8[4 * i + 1], t.rgba8[4 * i + 2], t.rgba8[4 * i + 3]) / 255.0f;
    case TexelFormat::Rgba16Unorm:
      return glm::vec4(t.rgba16[4 * i], t.rgba16[4 * i + 1], t.rgba16[4 * i + 2], t.rgba16[4 * i + 3]) / 65535.0f;
    case TexelFormat::Rgba16Float:
      return {glm::unpackHalf1x16(t.rgba16[4 * i]), glm::unpackHalf1x16(t.rgba16[4 * i + 1]),
              glm::unpackHalf1x16(t.rgba16[4 * i + 2]), glm::unpackHalf1x16(t.rgba16[4 * i + 3])};
  }
  return glm::vec4(0.0f);
}

std::optional<uint32_t> TextureCache::get(int textureIndex, bool srgb) {
  if (textureIndex < 0) return std::nullopt;
  if (auto it = cache_.find({textureIndex, srgb}); it != cache_.end()) return it->second;
  std::string name = fmt::format("texture{}", textureIndex);
  Texture t;
  t.srgb = srgb;
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
        t.source = ImageSource::File;
        t.path = file_.parent_path() / img.uri;
        if (img.name.empty()) name = t.path.stem().string();
        std::error_code ec;
        if (!std::filesystem::exists(t.path, ec)) error = "file not found";
        else ok = decode(OIIO::ImageInput::open(t.path.string()), t, error);
      } else if (!img.image.empty()) {
        // Embedded (a data: URI tinygltf has base64-decoded, or a .glb bufferView): from memory.
        // tinygltf clears the uri of a data: URI it decoded; a bufferView image has its index.
        t.source = img.bufferView >= 0 ? ImageSource::BufferView : ImageSource::DataUri;
        OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(img.image.data()), img.image.size());
        const std::string ext = sniffExtension(img.image, img.mimeType);
        ok = decode(OIIO::ImageInput::open(fmt::format("{}.{}", name, ext), nullptr, &reader), t, error);
      } else {
        error = "the image has no data";
      }
    }
  }
  if (!ok) {
    std::string where = t.path.empty() ? name : t.path.string();
    scene_.warnings.push_back(fmt::format("{}: texture {} could not be loaded ({}); using a magenta placeholder",
                                          file_.string(), where, oneLineError(error)));
    auto path = t.path;
    auto source = t.source;
    t = placeholder(name);
    t.path = path;
    t.source = source;
  }
  t.name = name;
  t.srgb = srgb;
  t.contentHash = hashTexels(t);
  uint32_t index = uint32_t(scene_.textures.size());
  scene_.textures.push_back(std::move(t));
  cache_[{textureIndex, srgb}] = index;
  return index;
}

}  // namespace tl::scene
