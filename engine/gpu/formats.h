// What the engine needs to know about a texel format to read it back and show it:
// bytes per texel, channel count, and a decoder to float (what the viewer, the NaN check
// and the EXR writer consume).
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tl::gpu {

enum class TexelKind : uint8_t { Float, Unorm, Srgb, Uint, Sint, Depth, Packed, Unknown };

struct FormatInfo {
  uint32_t bytes = 0;     // per texel
  uint32_t channels = 0;  // 1..4
  TexelKind kind = TexelKind::Unknown;
  const char* name = "UNKNOWN";  // short readable name, e.g. "RGBA16F"
};

FormatInfo formatInfo(VkFormat format);

// Decodes tightly packed texels to float, `channels` floats per texel (sRGB formats are
// returned as stored, i.e. not linearised; integer formats as their integer value).
std::vector<float> decodeTexels(VkFormat format, std::span<const uint8_t> bytes);

}  // namespace tl::gpu
