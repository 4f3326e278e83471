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

// Spreads `texels` pixels of `ch` channels, packed at the start of `p` (room for 4 each), to
// RGBA in place: grey -> rgb, a missing alpha -> `one`. Backwards, so that no pixel is
// overwritten before it is read; one loop per channel count, nothing decided per texel.
template <class T>
void widenToRgba(T* p, int ch, size_t texels, T one) {
  switch (ch) {
    case 1:
      for (size_t i = texels; i-- > 0;) {
        const T grey = p[i];
        p[4 * i] = p[4 * i + 1] = p[4 * i + 2] = grey, p[4 * i + 3] = one;
      }
      break;
    case 2:
      for (size_t i = texels; i-- > 0;) {
        const T grey = p[2 * i], alpha = p[2 * i + 1];
        p[4 * i] = p[4 * i + 1] = p[4 * i + 2] = grey, p[4 * i + 3] = alpha;
      }
      break;
    case 3:
      for (size_t i = texels; i-- > 0;) {
        const T r = p[3 * i], g = p[3 * i + 1], b = p[3 * i + 2];
        p[4 * i] = r, p[4 * i + 1] = g, p[4 * i + 2] = b, p[4 * i + 3] = one;
      }
      break;
    default:
      break;  // already RGBA
  }
}

// Reads every pixel (all `ch` channels) as `want` into `out`. OpenImageIO 2.4's read_image
// reads scanline images through a scratch buffer sized for 64 MB of scanlines whatever the
// image's height, even when no conversion is asked for (ImageInput::read_scanlines): a 64x64
// PNG allocated 64 MB per decode, which under AddressSanitizer cost milliseconds (poisoning
// its shadow) and held the image fuzzer to ~10 decodes a second on the shared machine. The
// scanlines are read as stored straight into a buffer of the image's size and converted here.
// Tiled images and per-channel types (OpenEXR) are left to read_image.
bool readPixels(OIIO::ImageInput& in, int ch, OIIO::TypeDesc want, void* out) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.tile_width != 0 || !spec.channelformats.empty()) return in.read_image(0, 0, 0, ch, want, out);
  const size_t values = size_t(spec.width) * size_t(spec.height) * size_t(ch);
  std::vector<std::byte> stored(spec.format == want ? 0 : values * spec.format.size());
  void* target = spec.format == want ? out : stored.data();
  if (!in.read_native_scanlines(0, 0, spec.y, spec.y + spec.height, 0, target)) return false;
  return spec.format == want || OIIO::convert_pixel_values(spec.format, target, want, out, int(values));
}

}  // namespace

std::vector<uint8_t> jpegWithoutMetadata(const std::vector<uint8_t>& bytes) {
  const size_t n = bytes.size();
  std::vector<uint8_t> out(bytes.begin(), bytes.begin() + std::min<size_t>(n, 2));  // SOI
  size_t pos = 2;
  while (pos < n) {
    while (pos < n && bytes[pos] != 0xFF) ++pos;  // libjpeg skips bytes between segments
    while (pos < n && bytes[pos] == 0xFF) ++pos;  // fill bytes
    if (pos >= n) break;
    const uint8_t marker = bytes[pos++];
    if (marker == 0x00) continue;  // a stuffed zero: not a marker
    if (marker == 0xDA || marker == 0xD9) {  // start of scan, end of image: the rest as it is
      out.push_back(0xFF);
      out.push_back(marker);
      out.insert(out.end(), bytes.begin() + ptrdiff_t(pos), bytes.end());
      return out;
    }
    const bool standalone = marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7);
    size_t end = pos;
    if (!standalone) {
      const size_t length = pos + 2 <= n ? (size_t(bytes[pos]) << 8 | bytes[pos + 1]) : 0;
      end = std::min(n, pos + 2 + (length >= 2 ? length - 2 : 0));
    }
    const bool metadata = (marker >= 0xE1 && marker <= 0xEF && marker != 0xEE) || marker == 0xFE;
    if (!metadata) {
      out.push_back(0xFF);
      out.push_back(marker);
      out.insert(out.end(), bytes.begin() + ptrdiff_t(pos), bytes.begin() + ptrdiff_t(end));
    }
    pos = end;
  }
  return out;
}

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
  // A JPEG's metadata never reaches OpenImageIO's parsers (jpegWithoutMetadata says why).
  const bool jpeg = std::strcmp(format, "jpeg") == 0;
  const std::vector<uint8_t> stripped = jpeg ? jpegWithoutMetadata(bytes) : std::vector<uint8_t>();
  const std::vector<uint8_t>& decoded = jpeg ? stripped : bytes;
  OIIO::Filesystem::IOMemReader reader(const_cast<uint8_t*>(decoded.data()), decoded.size());
  OIIO::ImageSpec opened;
  // glTF's colours are not premultiplied by alpha; OpenImageIO premultiplies a PNG's colour by
  // its alpha on reading unless told to keep it as stored (a texel of colour 10 and alpha 11
  // came back as colour 0.43 out of 255).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // The proxy is set after create(): OpenImageIO 2.4 drops one given to create() or in the
  // open() configuration for its PNG reader.
  auto in = OIIO::ImageInput::create(format);
  if (!in || !in->set_ioproxy(&reader) || !in->open(std::string("memory.") + format, opened, config)) {
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

  // Each pixel is read into the texture's own storage and widened to RGBA there.
  if (!isFloat && !deep) {
    t.format = TexelFormat::Rgba8;
    t.rgba8.resize(texels * 4);
    if (!readPixels(*in, ch, OIIO::TypeDesc::UINT8, t.rgba8.data())) {
      t.rgba8.clear();
      error = in->geterror();
      return false;
    }
    widenToRgba<uint8_t>(t.rgba8.data(), ch, texels, 255);
    return true;
  }
  if (deep && !t.srgb) {
    t.format = TexelFormat::Rgba16Unorm;
    t.rgba16.resize(texels * 4);
    if (!readPixels(*in, ch, OIIO::TypeDesc::UINT16, t.rgba16.data())) {
      t.rgba16.clear();
      error = in->geterror();
      return false;
    }
    widenToRgba<uint16_t>(t.rgba16.data(), ch, texels, 65535);
    return true;
  }
  // Float images, and 16-bit colour decoded from sRGB here (alpha stays linear).
  std::vector<float> pixels(texels * 4);
  if (!readPixels(*in, ch, OIIO::TypeDesc::FLOAT, pixels.data())) {
    error = in->geterror();
    return false;
  }
  widenToRgba<float>(pixels.data(), ch, texels, 1.0f);
  t.format = TexelFormat::Rgba16Float;
  t.rgba16.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    glm::vec4 v(pixels[4 * i], pixels[4 * i + 1], pixels[4 * i + 2], pixels[4 * i + 3]);
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
