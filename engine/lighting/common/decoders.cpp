#include "lighting/common/decoders.h"

#include "gpu/formats.h"
#include "shared/albedo.h"
#include "shared/color.h"
#include "shared/display.h"
#include "shared/packing.h"
#include "shared/rt.h"
#include "shared/sh.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace tl::lighting {
namespace {

// The texel's bytes, or null outside the resource.
const uint8_t* texelBytes(const graph::Readback& r, uint32_t x, uint32_t y, uint32_t z) {
  const uint32_t bpt = gpu::formatInfo(r.format).bytes;
  if (bpt == 0 || x >= r.extent.width || y >= r.extent.height || z >= std::max(1u, r.extent.depth)) return nullptr;
  const size_t offset = ((size_t(z) * r.extent.height + y) * r.extent.width + x) * bpt;
  return offset + bpt <= r.bytes.size() ? r.bytes.data() + offset : nullptr;
}

uint32_t uintAt(const graph::Readback& r, uint32_t x, uint32_t y, uint32_t z, uint32_t channel = 0) {
  const uint8_t* p = texelBytes(r, x, y, z);
  uint32_t v = 0;
  if (p) std::memcpy(&v, p + 4 * channel, 4);
  return v;
}

std::vector<float> floatsAt(const graph::Readback& r, uint32_t x, uint32_t y, uint32_t z) {
  const uint8_t* p = texelBytes(r, x, y, z);
  if (!p) return {};
  return gpu::decodeTexels(r.format, std::span<const uint8_t>(p, gpu::formatInfo(r.format).bytes));
}

// A companion's texel at the same relative position as (x, y) in `self`.
std::vector<float> companionAt(const DecodeInput& in, const std::string& name) {
  const graph::Readback* c = in.companion ? in.companion(name) : nullptr;
  if (!c || in.resource.extent.width == 0 || in.resource.extent.height == 0) return {};
  const uint32_t cx = uint32_t((uint64_t(in.x) * c->extent.width) / in.resource.extent.width);
  const uint32_t cy = uint32_t((uint64_t(in.y) * c->extent.height) / in.resource.extent.height);
  return floatsAt(*c, cx, cy, 0);
}

std::string vec(const glm::vec3& v, int digits = 4) { return fmt::format("{:.{}f} {:.{}f} {:.{}f}", v.x, digits, v.y, digits, v.z, digits); }

DecodedLines hitRecord(const DecodeInput& in, const DecoderSpec&) {
  const uint32_t hit = uintAt(in.resource, in.x, in.y, in.z);
  if (shared::tlRtIsMiss(hit)) return {{"ray", "miss: left the scene (sky)"}};
  if (shared::tlRtIsPending(hit)) return {{"ray", "pending: the pre-trace found nothing (a real ray is traced)"}};
  return {{"hit distance", fmt::format("{:.4f} m", shared::tlRtHitDistance(hit))},
          {"hit albedo", vec(shared::tlRtHitAlbedo(hit), 3)}};
}

DecodedLines hitSurface(const DecodeInput& in, const DecoderSpec&) {
  const uint32_t normal = uintAt(in.resource, in.x, in.y, in.z, 0), emission = uintAt(in.resource, in.x, in.y, in.z, 1);
  return {{"hit normal", vec(shared::tlOctDecodeSnorm16(normal))}, {"hit emission", vec(shared::tlUnpackRgb9e5(emission))}};
}

DecodedLines octNormal(const DecodeInput& in, const DecoderSpec&) {
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (v.size() < 2) return {};
  return {{"normal", vec(shared::tlOctDecode(glm::vec2(v[0], v[1])))}};
}

DecodedLines instanceId(const DecodeInput& in, const DecoderSpec&) {
  const uint32_t id = uintAt(in.resource, in.x, in.y, in.z);
  if (id == 0) return {{"instance", "none (background)"}};
  std::string name = in.scene && id - 1 < in.scene->instances.size() ? in.scene->instances[id - 1].name : "?";
  return {{"instance", fmt::format("{} (index {})", name, id - 1)}};
}

// A texel of L1 SH luma with what its spec's companions add: the chroma (zero where it was not
// read back) and the G-buffer normal to resolve it at (none where not read back).
struct ShTexel {
  shared::ShLumaCoCg sh;
  bool chroma = false;
  std::optional<glm::vec3> normal;
};
std::optional<ShTexel> shTexelAt(const DecodeInput& in, const DecoderSpec& spec) {
  auto y = floatsAt(in.resource, in.x, in.y, in.z);
  if (y.size() < 4) return std::nullopt;
  auto c = spec.companions.count("coCg") ? companionAt(in, spec.companions.at("coCg")) : std::vector<float>{};
  auto n = spec.companions.count("normal") ? companionAt(in, spec.companions.at("normal")) : std::vector<float>{};
  ShTexel t;
  t.chroma = c.size() >= 2;
  t.sh = shared::tlShMake(glm::vec4(y[0], y[1], y[2], y[3]), t.chroma ? glm::vec2(c[0], c[1]) : glm::vec2(0.0f));
  if (n.size() >= 2) t.normal = shared::tlOctDecode(glm::vec2(n[0], n[1]));
  return t;
}

DecodedLines shIrradiance(const DecodeInput& in, const DecoderSpec& spec) {
  const std::optional<ShTexel> t = shTexelAt(in, spec);
  if (!t) return {};
  DecodedLines out;
  if (!t->chroma) out.push_back({"chroma", "not read back: luma only"});
  if (t->normal) {
    out.push_back({"irradiance (at normal)", vec(shared::tlShResolveIrradiance(t->sh, *t->normal))});
    out.push_back({"normal", vec(*t->normal, 3)});
  }
  out.push_back({"dominant direction", vec(shared::tlShDominantDirection(t->sh, glm::vec3(0.0f, 1.0f, 0.0f)), 3)});
  out.push_back({"directionality", fmt::format("{:.3f}", shared::tlShDirectionality(t->sh))});
  return out;
}

DecodedLines albedoSource(const DecodeInput& in, const DecoderSpec&) {
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (v.size() < 4) return {};
  const char* source = v[3] == shared::kAlbedoSourceOverride ? "override"
                       : v[3] == shared::kAlbedoSourceBaked  ? "baked"
                       : v[3] == shared::kAlbedoSourceTextureAverage ? "texture average"
                                                                      : "no surface";
  return {{"albedo", vec(glm::vec3(v[0], v[1], v[2]), 3)}, {"source", source}};
}

// A group of path depths' radiance and its share of the pixel's whole radiance (luminance).
DecodedLines depthShare(const DecodeInput& in, const DecoderSpec& spec) {
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (v.size() < 3) return {};
  const glm::vec3 part(v[0], v[1], v[2]);
  DecodedLines out = {{"radiance", vec(part)}};
  auto w = spec.companions.count("whole") ? companionAt(in, spec.companions.at("whole")) : std::vector<float>{};
  if (w.size() < 3) {
    out.push_back({"share of the pixel", "whole radiance not read back"});
    return out;
  }
  const float whole = shared::tlLuminance(glm::vec3(w[0], w[1], w[2]));
  out.push_back({"share of the pixel", whole > 0.0f ? fmt::format("{:.1f}%", 100.0f * shared::tlLuminance(part) / whole)
                                                    : std::string("none (the pixel is black)")});
  return out;
}

// One of the I-buffer's sums of light (shared/redeferred.h): its value, luminance and what it
// weighs. A white dielectric would reflect about Ldg / pi of the diffuse share.
DecodedLines ibufferSum(const DecodeInput& in, const DecoderSpec& spec) {
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (v.size() < 3) return {};
  const std::string quantity = spec.name.substr(std::string_view(kIbufferDecoderPrefix).size());
  const glm::vec3 sum(v[0], v[1], v[2]);
  const char* meaning = quantity == "dg"    ? "sum of E n.l (1 - E_d(mu_i)): the diffuse layer's light"
                        : quantity == "sg1" ? "sum of E n.l D V: the specular lobe's light, F = 1"
                        : quantity == "sg2" ? "sum of E n.l D V (1 - v.h)^5: its Schlick-weighted part"
                                            : "sum of E n.l (1 - E(mu_i)): the multiple-scattering lobe's light";
  return {{"sum", vec(sum)}, {"luminance", fmt::format("{:.6g}", shared::tlLuminance(sum))}, {"weighs", meaning}};
}

// Ambient occlusion: the visibility the lighting multiplies by (other channels, e.g. the view
// depth a temporal filter keeps beside it, are shown by the raw values).
DecodedLines ambientOcclusion(const DecodeInput& in, const DecoderSpec&) {
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (v.empty()) return {};
  return {{"visibility", fmt::format("{:.3f} ({:.0f}% occluded)", v[0], 100.0f * (1.0f - v[0]))}};
}

// The clipmap's layout (shared/legacy.h): R from the height, levels stacked in z.
constexpr const char* kVoxelFaceNames[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
DecodedLines voxelFaces(const DecodeInput& in, const DecoderSpec&) {
  const uint32_t R = in.resource.extent.height;
  auto v = floatsAt(in.resource, in.x, in.y, in.z);
  if (R == 0 || v.size() < 4 || in.x / R >= 6) return {};
  return {{"face", fmt::format("{} (the radiance it sends towards {})", kVoxelFaceNames[in.x / R], kVoxelFaceNames[in.x / R])},
          {"voxel", fmt::format("level {}, x {} y {} z {} of {}", in.z / R, in.x % R, in.y, in.z % R, R)},
          {"radiance", vec(glm::vec3(v[0], v[1], v[2]))},
          {"opacity", fmt::format("{:.3f}", v[3])}};
}

// The default views (MeaningView) and their per-texel values, for the rows below.
std::optional<MeaningView> hitDistanceView(const DecoderSpec&) {
  return MeaningView{shared::kDisplayMeaningHitDistance, "hit distance", "m",
                     "near (blue) to far (red) over the range; dark blue-grey: miss (sky), grey: pending (traced later)",
                     true, true, {}};
}

float hitDistanceValue(const DecodeInput& in, const DecoderSpec&) {
  const uint32_t hit = uintAt(in.resource, in.x, in.y, in.z);
  return shared::tlRtIsHit(hit) ? shared::tlRtHitDistance(hit) : std::numeric_limits<float>::quiet_NaN();
}

constexpr const char* kDirectionLegend =
    "a direction as colour: red +X, green +Y, blue +Z; 0.5 grey = 0, darker = negative; no surface: near black";

std::optional<MeaningView> octNormalView(const DecoderSpec&) {
  return MeaningView{shared::kDisplayMeaningOctNormal, "shading normal", "", kDirectionLegend, false, false, {}};
}

std::optional<MeaningView> hitNormalView(const DecoderSpec&) {
  return MeaningView{shared::kDisplayMeaningHitNormal, "hit normal", "", kDirectionLegend, false, false, {}};
}

// Irradiance needs the chroma and the normal to resolve the SH at.
std::optional<MeaningView> shIrradianceView(const DecoderSpec& spec) {
  if (!spec.companions.count("coCg") || !spec.companions.count("normal")) return std::nullopt;
  return MeaningView{shared::kDisplayMeaningShIrradiance, "irradiance at the pixel normal", "W/m^2",
                     "what the SH resolves to at the G-buffer normal, over the range (black to white per channel)",
                     true, false, {spec.companions.at("coCg"), spec.companions.at("normal")}};
}

// The largest channel of the irradiance at the normal: what the RGB display's range must hold.
float shIrradianceValue(const DecodeInput& in, const DecoderSpec& spec) {
  const std::optional<ShTexel> t = shTexelAt(in, spec);
  if (!t || !t->chroma || !t->normal) return std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 e = shared::tlShResolveIrradiance(t->sh, *t->normal);
  return std::max({e.r, e.g, e.b});
}

std::optional<MeaningView> aoView(const DecoderSpec&) {
  return MeaningView{shared::kDisplayMeaningAo, "ambient occlusion", "",
                     "visibility as grey: white = open (1), black = fully occluded (0); no surface: near black",
                     false, false, {}};
}

// A slice of the clipmap: its level and world z voxel (R from the height, levels stacked in z).
std::optional<std::string> voxelSlice(const VkExtent3D& extent, uint32_t slice) {
  const uint32_t R = extent.height;
  if (R == 0 || std::max(1u, extent.depth) % R != 0) return std::nullopt;
  return fmt::format("level {}, world z voxel {} of {}", slice / R, slice % R, R);
}

// Every decoder, one row each: all the viewer asks of it. A new buffer view is a decode
// function (of the texel and the spec, whether or not it reads the spec's companions) and its row (a new default view also needs its kDisplayMeaning* in shared/display.h
// and the display shader's case).
struct DecoderRow {
  std::string_view name;
  bool namePrefix = false;  // the spec's name starts with `name` (ibuffer-dg, -sg1, ...)
  DecodedLines (*decode)(const DecodeInput&, const DecoderSpec&) = nullptr;
  // What the viewer shows by default; none: the stored values read as what they mean.
  std::optional<MeaningView> (*meaning)(const DecoderSpec&) = nullptr;
  // A fitted meaning's value at a texel, NaN where there is none.
  float (*meaningValue)(const DecodeInput&, const DecoderSpec&) = nullptr;
  bool negativesValid = false;  // signed by nature: directions, SH coefficients
  std::optional<std::string> (*slice)(const VkExtent3D&, uint32_t slice) = nullptr;  // what a 3D slice is
};

const DecoderRow kDecoderRows[] = {
    {.name = "rt-hit-record",
     .decode = hitRecord,
     .meaning = hitDistanceView,
     .meaningValue = hitDistanceValue},
    {.name = "rt-hit-surface",
     .decode = hitSurface,
     .meaning = hitNormalView,
     .negativesValid = true},
    {.name = "oct-normal",
     .decode = octNormal,
     .meaning = octNormalView,
     .negativesValid = true},
    {.name = "instance-id", .decode = instanceId},
    {.name = "sh-irradiance",
     .decode = shIrradiance,
     .meaning = shIrradianceView,
     .meaningValue = shIrradianceValue,
     .negativesValid = true},
    {.name = "albedo-source", .decode = albedoSource},
    {.name = kDepthShareDecoder, .decode = depthShare},
    {.name = kIbufferDecoderPrefix, .namePrefix = true, .decode = ibufferSum},
    {.name = "ao", .decode = ambientOcclusion, .meaning = aoView},
    {.name = "voxel-faces", .decode = voxelFaces, .slice = voxelSlice},
};

const DecoderRow* findDecoder(const DecoderSpec& spec) {
  for (const DecoderRow& row : kDecoderRows)
    if (row.namePrefix ? spec.name.rfind(row.name, 0) == 0 : spec.name == row.name) return &row;
  return nullptr;
}

}  // namespace

DecoderSpec parseDecoderSpec(const std::string& text) {
  DecoderSpec spec;
  std::istringstream in(text);
  in >> spec.name;
  for (std::string word; in >> word;) {
    auto eq = word.find('=');
    if (eq != std::string::npos) spec.companions[word.substr(0, eq)] = word.substr(eq + 1);
  }
  return spec;
}

std::vector<std::string> decoderCompanions(const std::string& text) {
  std::vector<std::string> out;
  for (auto& [role, name] : parseDecoderSpec(text).companions) out.push_back(name);
  return out;
}

DecodedLines rawTexel(const graph::Readback& r, uint32_t x, uint32_t y, uint32_t z) {
  const gpu::FormatInfo fi = gpu::formatInfo(r.format);
  const uint8_t* p = texelBytes(r, x, y, z);
  if (!p) return {{"texel", "outside the resource"}};
  DecodedLines out;
  static const char* kChannels[] = {"r", "g", "b", "a"};
  if (fi.kind == gpu::TexelKind::Uint || fi.kind == gpu::TexelKind::Sint) {
    // Channels of 1, 2 or 4 bytes (r8ui rooms, r32ui hit records), little-endian.
    const uint32_t size = fi.channels > 0 ? fi.bytes / fi.channels : 0;
    if (size != 1 && size != 2 && size != 4) return {{"texel", "unsupported integer layout"}};
    for (uint32_t c = 0; c < fi.channels && c < 4; ++c) {
      uint32_t v = 0;
      std::memcpy(&v, p + size * c, size);
      const int64_t value = fi.kind == gpu::TexelKind::Sint ? int64_t(int32_t(v)) : int64_t(v);  // sint: 32-bit only
      out.push_back({kChannels[c], fmt::format("{} (0x{:0{}x})", value, v, 2 * size)});
    }
    return out;
  }
  auto v = gpu::decodeTexels(r.format, std::span<const uint8_t>(p, fi.bytes));
  for (size_t c = 0; c < v.size() && c < 4; ++c) {
    // sRGB-encoded colour: also the linear value a shader samples (and a capture stores).
    if (fi.kind == gpu::TexelKind::Srgb && c < 3)
      out.push_back({kChannels[c], fmt::format("{:.6g} (linear {:.6g})", v[c], shared::tlSrgbToLinear1(v[c]))});
    else
      out.push_back({kChannels[c], fmt::format("{:.6g}", v[c])});
  }
  return out;
}

DecodedLines decodeTexel(const std::string& text, const DecodeInput& in) {
  const DecoderSpec spec = parseDecoderSpec(text);
  const DecoderRow* row = findDecoder(spec);
  return row ? row->decode(in, spec) : DecodedLines{};
}

std::optional<MeaningView> meaningView(const std::string& text) {
  const DecoderSpec spec = parseDecoderSpec(text);
  const DecoderRow* row = findDecoder(spec);
  return row && row->meaning ? row->meaning(spec) : std::nullopt;
}

std::vector<float> meaningValues(const std::string& text, const graph::Readback& r,
                                 const std::function<const graph::Readback*(const std::string&)>& companion) {
  const DecoderSpec spec = parseDecoderSpec(text);
  const DecoderRow* row = findDecoder(spec);
  const auto view = row && row->meaning ? row->meaning(spec) : std::nullopt;
  if (!view || !view->fitted || !row->meaningValue || r.extent.width == 0) return {};
  for (const std::string& c : view->companions)
    if (!companion || !companion(c)) return {};
  std::vector<float> out(size_t(r.extent.width) * r.extent.height);
  for (uint32_t y = 0; y < r.extent.height; ++y)
    for (uint32_t x = 0; x < r.extent.width; ++x)
      out[size_t(y) * r.extent.width + x] = row->meaningValue(DecodeInput{r, x, y, 0, companion, nullptr}, spec);
  return out;
}

bool negativesInvalid(const std::string& text, VkFormat format) {
  const DecoderRow* row = findDecoder(parseDecoderSpec(text));
  if (row && row->negativesValid) return false;
  switch (format) {
    case VK_FORMAT_R8_SNORM: case VK_FORMAT_R8G8_SNORM: case VK_FORMAT_R8G8B8A8_SNORM: case VK_FORMAT_R16_SNORM:
    case VK_FORMAT_R16G16_SNORM: case VK_FORMAT_R16G16B16A16_SNORM: return false;  // signed by choice
    default: return true;
  }
}

std::string sliceMeaning(const std::string& text, const VkExtent3D& extent, uint32_t slice) {
  const uint32_t depth = std::max(1u, extent.depth);
  slice = std::min(slice, depth - 1);  // what the display shows for a slice past the end
  const DecoderRow* row = findDecoder(parseDecoderSpec(text));
  if (row && row->slice)
    if (std::optional<std::string> named = row->slice(extent, slice)) return *named;
  return fmt::format("z {} of {}", slice, depth);
}

}  // namespace tl::lighting
