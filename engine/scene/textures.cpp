// Texture images: read under the limits of scene/input_limits.h and decoded by OpenImageIO
// from memory, as PNG or JPEG (the formats glTF allows) or OpenEXR / Radiance HDR (float
// images), chosen by the bytes' signature only, so neither the file's name nor its extension
// can send the bytes to any other of OpenImageIO's decoders. Texels keep their precision
// (scene.h TexelFormat).
#include "scene/input_limits.h"
#include "scene/scene_internal.h"

#include <tiny_gltf.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>

#include "shared/color.h"

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
  static const uint8_t exr[] = {0x76, 0x2F, 0x31, 0x01};
  if (bytes.size() >= 4 && std::equal(exr, exr + 4, bytes.begin())) return "openexr";
  auto startsWith = [&](const char* magic) {
    const size_t n = std::strlen(magic);
    return bytes.size() >= n && std::equal(magic, magic + n, bytes.begin());
  };
  if (startsWith("#?RADIANCE") || startsWith("#?RGBE")) return "hdr";
  return nullptr;
}

// Channel c (0..3) of an RGBA texel from `ch` stored channels: grey -> rgb, missing alpha -> one.
template <class T>
T expand(const T* s, int ch, int c, T one) {
  if (c < 3) return ch >= 3 ? s[c] : s[0];
  return ch == 2 ? s[1] : ch >= 4 ? s[3] : one;
}

}  // namespace

// glTF 3.8.4: wrap REPEAT (10497), CLAMP_TO_EDGE (33071), MIRRORED_REPEAT (33648); filters
// NEAREST (9728), LINEAR (9729) and the four mipmap minifications. No sampler, or an
// undefined filter: repeat and (tri)linear, Twinlight's choice where glTF leaves it open.
SamplerMode samplerMode(const tinygltf::Model& model, int samplerIndex) {
  SamplerMode s;
  if (samplerIndex < 0 || size_t(samplerIndex) >= model.samplers.size()) return s;
  const auto& g = model.samplers[size_t(samplerIndex)];
  auto wrap = [](int mode) {
    return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? Wrap::ClampToEdge
           : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? Wrap::MirroredRepeat
                                                           : Wrap::Repeat;
  };
  s.wrapS = wrap(g.wrapS);
  s.wrapT = wrap(g.wrapT);
  s.magNearest = g.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  s.minNearest = g.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST || g.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                 g.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
  // Without mipmaps (NEAREST, LINEAR) the finest level is read: nearest level selection with
  // maxLod 0 is set where the sampler is made (gpu_scene.cpp).
  s.mipNearest = g.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                 g.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST;
  s.noMipmaps = g.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST || g.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR;
  return s;
}

bool decodeImage(const std::vector<uint8_t>& bytes, Texture& t, std::string& error) {
  const char* format = formatOf(bytes);
  if (!format) {
    error = "neither PNG, JPEG, OpenEXR nor Radiance HDR";
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
  const size_t texels = size_t(spec.width) * size_t(spec.height);
  t.width = uint32_t(spec.width);
  t.height = uint32_t(spec.height);
  t.fileFormat = format;
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
  t.srgb = srgb;  // decodeImage turns 16-bit colour into linear half floats
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
        // Embedded: tinygltf clears the uri of a data: URI it decoded; a bufferView image has its index.
        t.source = img.bufferView >= 0 ? ImageSource::BufferView : ImageSource::DataUri;
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
    auto source = t.source;
    t = placeholder(name);
    t.path = path;
    t.source = source;
  }
  t.name = name;
  t.srgb = srgb;
  t.contentHash = hashTexels(t);
  if (size_t(textureIndex) < model_.textures.size()) t.sampler = samplerMode(model_, model_.textures[size_t(textureIndex)].sampler);
  uint32_t index = uint32_t(scene_.textures.size());
  scene_.textures.push_back(std::move(t));
  cache_[{textureIndex, srgb}] = index;
  return index;
}

}  // namespace tl::scene
