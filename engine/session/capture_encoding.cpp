#include "session/capture_encoding.h"

#include "gpu/formats.h"
#include "session/session.h"
#include "shared/color.h"
#include "shared/packing.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace tl::session {
namespace {

std::vector<std::string> channelNames(const graph::ResourceDesc& desc, uint32_t count) {
  std::vector<std::string> names;
  std::istringstream in(desc.channels);
  for (std::string word; in >> word;) names.push_back(word);
  if (names.size() == count) return names;
  if (count == 1) return {"Y"};
  static const char* kRgba[] = {"R", "G", "B", "A"};
  return std::vector<std::string>(kRgba, kRgba + std::min(count, 4u));
}

// A depth format not declared as the camera's Z (a shadow map): raw device depth.
std::vector<std::string> depthOr(std::vector<std::string> names, const gpu::FormatInfo& fi) {
  if (fi.kind == gpu::TexelKind::Depth && names == std::vector<std::string>{"Y"}) return {"depth"};
  return names;
}

bool isReversedDepth(const graph::ResourceDesc& desc, const gpu::FormatInfo& fi) {
  return fi.kind == gpu::TexelKind::Depth && desc.channels == "Z";
}

}  // namespace

StoredImage encodeCaptureImage(const graph::ResourceDesc& desc, const graph::Readback& image, float znear) {
  const gpu::FormatInfo fi = gpu::formatInfo(image.format);
  StoredImage out;
  out.width = image.extent.width;
  out.height = image.extent.height * std::max(1u, image.extent.depth);
  const uint32_t n = fi.channels;
  const size_t texels = size_t(out.width) * out.height;
  const std::vector<float> texelValues = image.texels();
  if (texelValues.size() < texels * n)
    throw SessionError(fmt::format("`{}` ({}) cannot be captured as an image", image.name, fi.name));
  out.fileExtension = ".exr";

  if (fi.kind == gpu::TexelKind::Uint || fi.kind == gpu::TexelKind::Sint) {
    out.encoding = "uint";
    out.channels = channelNames(desc, n);
    out.integers.resize(texels * n);
    if (fi.bytes == 4u * n) std::memcpy(out.integers.data(), image.bytes.data(), out.integers.size() * 4);
    else
      for (size_t i = 0; i < out.integers.size(); ++i) out.integers[i] = uint32_t(int64_t(texelValues[i]));
    out.meaning = "exact integers as stored";
    return out;
  }
  if (desc.display) {
    out.encoding = "display";
    out.fileExtension = ".png";
    out.channels = {"R", "G", "B"};  // a display image's alpha means nothing on a screen
    out.values.resize(texels * 3);
    for (size_t t = 0; t < texels; ++t)
      for (uint32_t c = 0; c < 3; ++c) out.values[t * 3 + c] = c < n ? texelValues[t * n + c] : 0.0f;
    out.meaning = "display-referred: tonemapped and sRGB-encoded, as shown on screen (not scene-linear)";
    return out;
  }
  if (isReversedDepth(desc, fi)) {
    // Reversed Z with an infinite far plane: d = near / viewDepth (gbuffer_pass.h).
    out.encoding = "view-depth";
    out.channels = {"Z"};
    out.values.resize(texels);
    for (size_t t = 0; t < texels; ++t) {
      const float d = texelValues[t];
      out.values[t] = d > 0.0f ? znear / d : std::numeric_limits<float>::infinity();
    }
    out.meaning = fmt::format("view depth along the camera axis in metres (inf: nothing drawn), from reversed Z with near {}", znear);
    return out;
  }
  if (desc.decoder == "oct-normal" && n >= 2) {
    out.encoding = "normal";
    out.channels = {"N.x", "N.y", "N.z"};
    out.values.resize(texels * 3);
    for (size_t t = 0; t < texels; ++t) {
      const glm::vec3 v = shared::tlOctDecode(glm::vec2(texelValues[t * n], texelValues[t * n + 1]));
      out.values[t * 3 + 0] = v.x, out.values[t * 3 + 1] = v.y, out.values[t * 3 + 2] = v.z;
    }
    out.meaning = "unit normal vector, world space (decoded from the octahedral encoding)";
    return out;
  }
  out.channels = depthOr(channelNames(desc, n), fi);
  out.values = texelValues;
  out.values.resize(texels * n);
  if (fi.kind == gpu::TexelKind::Srgb) {
    out.encoding = "srgb-decoded";
    for (size_t t = 0; t < texels; ++t)
      for (uint32_t c = 0; c < std::min(n, 3u); ++c) out.values[t * n + c] = shared::tlSrgbToLinear1(out.values[t * n + c]);
    out.half = true;
    out.meaning = "linear values (the stored sRGB encoding decoded, as a shader samples it); alpha as stored";
    return out;
  }
  // Half where it holds every stored value exactly: 16-bit floats and 8-bit normalised values
  // (16-bit normalised values need more than half's 11 bits).
  const uint32_t bytesPerChannel = n ? fi.bytes / n : 4;
  out.encoding = "linear";
  out.half = (fi.kind == gpu::TexelKind::Float && bytesPerChannel == 2) || bytesPerChannel == 1;
  out.meaning = "values as stored" + (desc.description.empty() ? std::string() : ": " + desc.description);
  return out;
}

std::vector<float> decodeCaptureValues(const std::string& encoding, const std::string& formatName,
                                       const std::vector<float>& stored, uint32_t storedChannels, uint32_t channels,
                                       float znear) {
  const uint32_t sc = std::max(1u, storedChannels);
  const size_t texels = stored.size() / sc;
  std::vector<float> out(texels * channels, 0.0f);
  // Missing channels: a display image's alpha and any padding are opaque.
  auto copyChannels = [&] {
    for (size_t t = 0; t < texels; ++t)
      for (uint32_t c = 0; c < channels; ++c) out[t * channels + c] = c < sc ? stored[t * sc + c] : 1.0f;
  };
  if (encoding == "linear" || encoding == "uint" || encoding == "display" || encoding == "srgb-decoded") {
    copyChannels();  // srgb-decoded stays linear: what sampling the sRGB image gives a shader
  } else if (encoding == "view-depth") {
    for (size_t t = 0; t < texels; ++t) {
      const float z = stored[t * sc];
      out[t * channels] = std::isfinite(z) && z > 0.0f ? znear / z : 0.0f;
    }
  } else if (encoding == "normal") {
    // Back to the octahedral encoding the viewer's decoder reads; a 16-bit snorm original is
    // snapped to its grid, which gives its exact values back.
    const bool snorm16 = formatName.find("16_SNORM") != std::string::npos;
    for (size_t t = 0; t < texels; ++t) {
      glm::vec2 e = shared::tlOctEncode(glm::vec3(stored[t * sc], stored[t * sc + 1], stored[t * sc + 2]));
      if (snorm16) e = glm::max(glm::round(e * 32767.0f) / 32767.0f, glm::vec2(-1.0f));
      for (uint32_t c = 0; c < channels; ++c) out[t * channels + c] = c < 2 ? e[int(c)] : 0.0f;
    }
  } else {
    throw SessionError(fmt::format("unknown capture encoding `{}`", encoding));
  }
  return out;
}

}  // namespace tl::session
