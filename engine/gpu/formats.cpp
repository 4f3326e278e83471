#include "gpu/formats.h"

#include "gpu/check.h"

#include <glm/gtc/packing.hpp>

#include <cstring>

namespace tl::gpu {

FormatInfo formatInfo(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM: return {1, 1, TexelKind::Unorm, "R8"};
    case VK_FORMAT_R8G8_UNORM: return {2, 2, TexelKind::Unorm, "RG8"};
    case VK_FORMAT_R8G8B8A8_UNORM: return {4, 4, TexelKind::Unorm, "RGBA8"};
    case VK_FORMAT_B8G8R8A8_UNORM: return {4, 4, TexelKind::Unorm, "BGRA8"};
    case VK_FORMAT_R8G8B8A8_SRGB: return {4, 4, TexelKind::Srgb, "RGBA8_SRGB"};
    case VK_FORMAT_B8G8R8A8_SRGB: return {4, 4, TexelKind::Srgb, "BGRA8_SRGB"};
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32: return {4, 4, TexelKind::Packed, "RGB10A2"};
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32: return {4, 3, TexelKind::Packed, "R11G11B10F"};
    case VK_FORMAT_R16_SFLOAT: return {2, 1, TexelKind::Float, "R16F"};
    case VK_FORMAT_R16G16_SFLOAT: return {4, 2, TexelKind::Float, "RG16F"};
    case VK_FORMAT_R16G16B16A16_SFLOAT: return {8, 4, TexelKind::Float, "RGBA16F"};
    case VK_FORMAT_R16G16_SNORM: return {4, 2, TexelKind::Unorm, "RG16_SNORM"};
    case VK_FORMAT_R16G16B16A16_UNORM: return {8, 4, TexelKind::Unorm, "RGBA16"};
    case VK_FORMAT_R32_SFLOAT: return {4, 1, TexelKind::Float, "R32F"};
    case VK_FORMAT_R32G32_SFLOAT: return {8, 2, TexelKind::Float, "RG32F"};
    case VK_FORMAT_R32G32B32A32_SFLOAT: return {16, 4, TexelKind::Float, "RGBA32F"};
    case VK_FORMAT_R32_UINT: return {4, 1, TexelKind::Uint, "R32UI"};
    case VK_FORMAT_R32G32_UINT: return {8, 2, TexelKind::Uint, "RG32UI"};
    case VK_FORMAT_R32G32B32A32_UINT: return {16, 4, TexelKind::Uint, "RGBA32UI"};
    case VK_FORMAT_R16_UINT: return {2, 1, TexelKind::Uint, "R16UI"};
    case VK_FORMAT_R8_UINT: return {1, 1, TexelKind::Uint, "R8UI"};
    case VK_FORMAT_D32_SFLOAT: return {4, 1, TexelKind::Depth, "D32F"};
    case VK_FORMAT_D16_UNORM: return {2, 1, TexelKind::Depth, "D16"};
    default: return {};
  }
}

std::vector<float> decodeTexels(VkFormat format, std::span<const uint8_t> bytes) {
  FormatInfo fi = formatInfo(format);
  if (fi.bytes == 0) throw Error("cannot decode texels of an unknown format");
  size_t texels = bytes.size() / fi.bytes;
  std::vector<float> out(texels * fi.channels);
  const uint8_t* p = bytes.data();
  for (size_t t = 0; t < texels; ++t, p += fi.bytes) {
    float* o = &out[t * fi.channels];
    switch (format) {
      case VK_FORMAT_R16_SFLOAT: case VK_FORMAT_R16G16_SFLOAT: case VK_FORMAT_R16G16B16A16_SFLOAT:
        for (uint32_t c = 0; c < fi.channels; ++c) {
          uint16_t h;
          std::memcpy(&h, p + 2 * c, 2);
          o[c] = glm::unpackHalf1x16(h);
        }
        break;
      case VK_FORMAT_R32_SFLOAT: case VK_FORMAT_R32G32_SFLOAT: case VK_FORMAT_R32G32B32A32_SFLOAT:
      case VK_FORMAT_D32_SFLOAT:
        std::memcpy(o, p, 4 * fi.channels);
        break;
      case VK_FORMAT_R32_UINT: case VK_FORMAT_R32G32_UINT: case VK_FORMAT_R32G32B32A32_UINT:
        for (uint32_t c = 0; c < fi.channels; ++c) {
          uint32_t u;
          std::memcpy(&u, p + 4 * c, 4);
          o[c] = float(u);
        }
        break;
      case VK_FORMAT_R16_UINT: { uint16_t u; std::memcpy(&u, p, 2); o[0] = float(u); break; }
      case VK_FORMAT_R8_UINT: o[0] = float(p[0]); break;
      case VK_FORMAT_D16_UNORM: { uint16_t u; std::memcpy(&u, p, 2); o[0] = u / 65535.0f; break; }
      case VK_FORMAT_R16G16B16A16_UNORM:
        for (uint32_t c = 0; c < 4; ++c) {
          uint16_t u;
          std::memcpy(&u, p + 2 * c, 2);
          o[c] = u / 65535.0f;
        }
        break;
      case VK_FORMAT_R16G16_SNORM:
        for (uint32_t c = 0; c < 2; ++c) {
          int16_t s;
          std::memcpy(&s, p + 2 * c, 2);
          o[c] = std::max(-1.0f, s / 32767.0f);
        }
        break;
      case VK_FORMAT_B8G8R8A8_UNORM: case VK_FORMAT_B8G8R8A8_SRGB:
        o[0] = p[2] / 255.0f, o[1] = p[1] / 255.0f, o[2] = p[0] / 255.0f, o[3] = p[3] / 255.0f;
        break;
      case VK_FORMAT_A2B10G10R10_UNORM_PACK32: {
        uint32_t u;
        std::memcpy(&u, p, 4);
        o[0] = (u & 1023) / 1023.0f, o[1] = ((u >> 10) & 1023) / 1023.0f, o[2] = ((u >> 20) & 1023) / 1023.0f;
        o[3] = (u >> 30) / 3.0f;
        break;
      }
      case VK_FORMAT_B10G11R11_UFLOAT_PACK32: {
        uint32_t u;
        std::memcpy(&u, p, 4);
        glm::vec3 v = glm::unpackF2x11_1x10(u);
        o[0] = v.x, o[1] = v.y, o[2] = v.z;
        break;
      }
      default:  // 8-bit unorm / srgb
        for (uint32_t c = 0; c < fi.channels; ++c) o[c] = p[c] / 255.0f;
        break;
    }
  }
  return out;
}

}  // namespace tl::gpu
