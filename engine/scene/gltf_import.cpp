// glTF 2.0 import with tinygltf. The file is read here, under the limits of
// scene/input_limits.h (a regular file, its size, its JSON nesting), then tinygltf parses the
// JSON and loads buffers through callbacks that apply the same rules; images are read and
// decoded here with OpenImageIO (textures.cpp) so we control missing files. Every accessor
// read is bounds-checked here with overflow-safe arithmetic, and every number is checked
// after conversion to float (scene/import_values.h): tinygltf validates neither, and a
// malformed file must produce one clear error, never a crash.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "scene/import_values.h"
#include "scene/input_limits.h"
#include "scene/morph.h"
#include "scene/node_animation.h"
#include "scene/skinning.h"
#include "scene/scene_internal.h"

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <optional>
#include <set>

namespace tl::scene {
namespace {

std::string oneLine(std::string s) {
  for (auto& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  if (s.size() > 300) s = s.substr(0, 300) + "...";
  return s;
}

// tinygltf would otherwise decode images itself; we keep the bytes (for embedded images)
// and decode later so a missing texture is a warning, not a failed load. `user` is the model
// being loaded: tinygltf 2.7 hands over an image's bufferView without checking that the view
// lies inside its buffer (fuzz_gltf: a heap-buffer-overflow reading past a 209-byte buffer),
// so the view is checked here before a byte of it is read.
bool keepImageBytes(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* user) {
  const auto& model = *static_cast<const tinygltf::Model*>(user);
  if (image->bufferView >= 0) {
    const auto& views = model.bufferViews;
    const bool viewExists = size_t(image->bufferView) < views.size();
    const auto* view = viewExists ? &views[size_t(image->bufferView)] : nullptr;
    uint64_t end = 0;
    if (!view || view->buffer < 0 || size_t(view->buffer) >= model.buffers.size() ||
        __builtin_add_overflow(uint64_t(view->byteOffset), uint64_t(view->byteLength), &end) ||
        end > model.buffers[size_t(view->buffer)].data.size() || view->byteLength > uint64_t(INT32_MAX)) {
      if (err) *err += fmt::format("image {} refers to bufferView {}, which reaches past the end of its buffer", index,
                                   image->bufferView);
      return false;
    }
  }
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// Buffers named by URI are read through these callbacks under the rules images follow
// (readReferencedFile): no shell expansion, regular files, sizes, the scene's folder.
struct BufferAccess {
  const std::filesystem::path& gltfFile;
  const LoadOptions& options;
  std::string refusal;  // the first buffer refused, and why
};

bool fileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

std::string expandNothing(const std::string& path, void*) { return path; }

bool readBuffer(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& access = *static_cast<BufferAccess*>(user);
  try {
    *out = readContained(access.gltfFile, path, access.options, InputLimits::kMaxFileBytes);
    return true;
  } catch (const InputFileError& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    if (err) *err += e.what();
    return false;
  }
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the importer writes no files";
  return false;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (as much of it as the file holds).
std::string_view jsonText(const std::vector<uint8_t>& bytes, bool binary) {
  const char* text = reinterpret_cast<const char*>(bytes.data());
  if (!binary || bytes.size() < 20) return {text, bytes.size()};
  uint32_t chunkLength = 0;
  std::memcpy(&chunkLength, bytes.data() + 12, 4);
  return {text + 20, std::min<size_t>(chunkLength, bytes.size() - 20)};
}

class Reader {
 public:
  Reader(const tinygltf::Model& m, const std::filesystem::path& file) : m_(m), file_(file) {}

  [[noreturn]] void fail(const std::string& what) const { throw SceneError(fmt::format("{}: {}", file_.string(), what)); }

  // Returns the element pointer, count and stride of an accessor after checking that every
  // element lies inside its buffer.
  struct View {
    const uint8_t* data = nullptr;
    size_t count = 0;
    size_t stride = 0;
    int componentType = 0;
    int type = 0;
    bool normalized = false;
  };

  View accessor(int index, const char* what) const {
    if (index < 0 || size_t(index) >= m_.accessors.size()) fail(fmt::format("{} refers to accessor {}, which does not exist", what, index));
    const auto& a = m_.accessors[size_t(index)];
    View v;
    v.count = a.count;
    v.componentType = a.componentType;
    v.type = a.type;
    v.normalized = a.normalized;
    // A sparse accessor may have no bufferView: its base values are zeros.
    if (a.sparse.isSparse && a.bufferView < 0) {
      v.stride = elementBytes(a, index, what);
      zeros_.emplace_back(v.count * v.stride, uint8_t(0));
      v.data = zeros_.back().data();
      return v;
    }
    if (a.bufferView < 0 || size_t(a.bufferView) >= m_.bufferViews.size())
      fail(fmt::format("accessor {} ({}) has no valid bufferView", index, what));
    const auto& bv = m_.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size()) fail(fmt::format("bufferView {} refers to a missing buffer", a.bufferView));
    const auto& buf = m_.buffers[size_t(bv.buffer)].data;
    int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (compSize <= 0 || comps <= 0) fail(fmt::format("accessor {} ({}) has an invalid type", index, what));
    size_t elem = size_t(compSize) * size_t(comps);
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) fail(fmt::format("accessor {} ({}) has a byteStride smaller than its element", index, what));
    // Every sum and product checked: offsets and counts near 2^64 in a hostile file would
    // wrap an unchecked bound and read in front of the buffer.
    uint64_t needed = 0, accessorEnd = 0, begin = 0, viewEnd = 0;
    bool overflow = false;
    if (v.count > 0)
      overflow |= __builtin_mul_overflow(uint64_t(v.count - 1), uint64_t(v.stride), &needed) ||
                  __builtin_add_overflow(needed, uint64_t(elem), &needed);
    overflow |= __builtin_add_overflow(uint64_t(a.byteOffset), needed, &accessorEnd);
    overflow |= __builtin_add_overflow(uint64_t(bv.byteOffset), uint64_t(a.byteOffset), &begin);
    overflow |= __builtin_add_overflow(uint64_t(bv.byteOffset), uint64_t(bv.byteLength), &viewEnd);
    if (overflow || accessorEnd > bv.byteLength || viewEnd > buf.size())
      fail(fmt::format("accessor {} ({}) reaches past the end of its buffer ({} elements of {} bytes from offset {} "
                       "of bufferView {} at {}, buffer has {} bytes)",
                       index, what, v.count, elem, a.byteOffset, a.bufferView, bv.byteOffset, buf.size()));
    v.data = buf.data() + begin;
    return v;
  }

  float component(const View& v, size_t i, int c) const {
    int size = tinygltf::GetComponentSizeInBytes(uint32_t(v.componentType));
    const uint8_t* p = v.data + i * v.stride + size_t(c) * size_t(size);
    switch (v.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[0] / 255.0f : float(p[0]);
      case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t s; std::memcpy(&s, p, 1); return v.normalized ? std::max(s / 127.0f, -1.0f) : float(s); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); return v.normalized ? u / 65535.0f : float(u); }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t s; std::memcpy(&s, p, 2); return v.normalized ? std::max(s / 32767.0f, -1.0f) : float(s); }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); return float(u); }
      default: fail("unsupported accessor component type");
    }
  }

  template <int N>
  std::vector<glm::vec<N, float>> floats(int index, const char* what) const {
    View v = accessor(index, what);
    if (tinygltf::GetNumComponentsInType(uint32_t(v.type)) != N)
      fail(fmt::format("accessor {} ({}) has {} components, expected {}", index, what,
                       tinygltf::GetNumComponentsInType(uint32_t(v.type)), N));
    std::vector<glm::vec<N, float>> out(v.count);
    for (size_t i = 0; i < v.count; ++i)
      for (int c = 0; c < N; ++c) out[i][c] = component(v, i, c);
    applySparse(index, what, [&](size_t target, const View& values, size_t k) {
      for (int c = 0; c < N; ++c) out[target][c] = component(values, k, c);
    });
    return out;
  }

  // MAT4 elements, column-major as glTF stores them.
  std::vector<glm::dmat4> matrices(int index, const char* what) const {
    View v = accessor(index, what);
    if (v.type != TINYGLTF_TYPE_MAT4) fail(fmt::format("accessor {} ({}) is not MAT4", index, what));
    std::vector<glm::dmat4> out(v.count);
    for (size_t i = 0; i < v.count; ++i)
      for (int c = 0; c < 16; ++c) out[i][c / 4][c % 4] = component(v, i, c);
    applySparse(index, what, [&](size_t target, const View& values, size_t k) {
      for (int c = 0; c < 16; ++c) out[target][c / 4][c % 4] = component(values, k, c);
    });
    return out;
  }

  std::vector<uint32_t> indices(int index) const {
    View v = accessor(index, "indices");
    if (v.type != TINYGLTF_TYPE_SCALAR) fail(fmt::format("index accessor {} is not scalar", index));
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      const uint8_t* p = v.data + i * v.stride;
      switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = p[0]; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); out[i] = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
        default: fail(fmt::format("index accessor {} has a component type indices cannot have", index));
      }
    }
    applySparse(index, "indices", [&](size_t target, const View& values, size_t k) {
      out[target] = uint32_t(component(values, k, 0));
    });
    return out;
  }

 private:
  size_t elementBytes(const tinygltf::Accessor& a, int index, const char* what) const {
    int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (compSize <= 0 || comps <= 0) fail(fmt::format("accessor {} ({}) has an invalid type", index, what));
    return size_t(compSize) * size_t(comps);
  }

  // A checked view of `count` tightly packed elements in bufferView `view` from `offset`.
  View packed(int view, size_t offset, size_t count, int componentType, int type, bool normalized, int index,
              const char* what) const {
    if (view < 0 || size_t(view) >= m_.bufferViews.size())
      fail(fmt::format("sparse accessor {} ({}) refers to bufferView {}, which does not exist", index, what, view));
    const auto& bv = m_.bufferViews[size_t(view)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size()) fail(fmt::format("bufferView {} refers to a missing buffer", view));
    int compSize = tinygltf::GetComponentSizeInBytes(uint32_t(componentType));
    int comps = tinygltf::GetNumComponentsInType(uint32_t(type));
    if (compSize <= 0 || comps <= 0) fail(fmt::format("sparse accessor {} ({}) has an invalid type", index, what));
    const size_t elem = size_t(compSize) * size_t(comps), bytes = count * elem;
    const auto& buf = m_.buffers[size_t(bv.buffer)].data;
    if (offset + bytes > bv.byteLength || bv.byteOffset + bv.byteLength > buf.size())
      fail(fmt::format("sparse accessor {} ({}) reaches past the end of bufferView {}", index, what, view));
    View v;
    v.data = buf.data() + bv.byteOffset + offset;
    v.count = count;
    v.stride = elem;
    v.componentType = componentType;
    v.type = type;
    v.normalized = normalized;
    return v;
  }

  // Sparse accessors (glTF 3.6.2.3): `count` indices into the accessor and as many values that
  // replace the base values there; calls set(target element, values view, k) for each.
  template <class Set>
  void applySparse(int index, const char* what, Set set) const {
    const auto& a = m_.accessors[size_t(index)];
    if (!a.sparse.isSparse) return;
    const size_t n = size_t(std::max(a.sparse.count, 0));
    View idx = packed(a.sparse.indices.bufferView, size_t(a.sparse.indices.byteOffset), n, a.sparse.indices.componentType,
                      TINYGLTF_TYPE_SCALAR, false, index, what);
    View values = packed(a.sparse.values.bufferView, size_t(a.sparse.values.byteOffset), n, a.componentType, a.type,
                         a.normalized, index, what);
    for (size_t k = 0; k < n; ++k) {
      const double target = component(idx, k, 0);
      if (!(target >= 0.0 && target < double(a.count)))
        fail(fmt::format("sparse accessor {} ({}) replaces element {}, beyond its {} elements", index, what, target, a.count));
      set(size_t(target), values, k);
    }
  }

  const tinygltf::Model& m_;
  const std::filesystem::path& file_;
  mutable std::vector<std::vector<uint8_t>> zeros_;  // base values of sparse accessors without a bufferView
};

// The node's local transform as animation needs it: TRS, or the matrix a file gives instead.
Node localNode(const tinygltf::Node& n, int index) {
  Node out;
  out.name = n.name.empty() ? fmt::format("node{}", index) : n.name;
  if (n.matrix.size() == 16) out.matrix = glm::make_mat4(n.matrix.data());
  if (n.translation.size() == 3) out.translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
  if (n.rotation.size() == 4) out.rotation = glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) out.scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
  return out;
}

// Finite once stored as float, and placing things within InputLimits::kMaxCoordinate.
bool usableTransform(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(float(m[c][r]))) return false;
  return std::abs(m[3][0]) <= InputLimits::kMaxCoordinate && std::abs(m[3][1]) <= InputLimits::kMaxCoordinate &&
         std::abs(m[3][2]) <= InputLimits::kMaxCoordinate;
}

// Normals are transformed by the inverse transpose: a singular transform (a zero scale) has
// none, and the float version of it must be finite too.
bool invertible(const glm::dmat4& m) {
  const glm::dmat3 l(m);
  const double det = glm::determinant(l);
  if (!std::isfinite(det) || std::abs(det) < 1e-30) return false;
  const glm::mat3 n(glm::transpose(glm::inverse(l)));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(n[c][r])) return false;
  return true;
}

template <int N>
bool allFinite(const glm::vec<N, double>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

bool withinWorld(const Bounds& b) {
  if (!b.valid()) return true;
  const double most = std::max({std::abs(b.min.x), std::abs(b.min.y), std::abs(b.min.z), std::abs(b.max.x),
                                std::abs(b.max.y), std::abs(b.max.z)});
  return most <= InputLimits::kMaxCoordinate;
}

// One KHR_lights_punctual light at its node's place. One rule with the rest of the import
// (ImportValues): a plain value out of range is clamped with one warning naming the light
// (negative light does not exist: 0), a value that is not a finite float or beyond the light
// limit is one error, and data the specification forbids (an unknown type, a colour of other
// than 3 numbers, cones with inner >= outer or outside [0, pi/2]) is one error, not a guess.
// Returns nothing, with a warning, when the node's transform leaves no direction.
std::optional<Light> readLight(const tinygltf::Light& gl, const std::string& nodeName, const glm::dvec3& position,
                               const glm::dquat& orientation, ImportValues& values) {
  Light l;
  l.name = gl.name.empty() ? nodeName : gl.name;
  const std::string what = fmt::format("light `{}`", l.name);
  if (gl.type == "directional") l.type = LightType::Directional;
  else if (gl.type == "point") l.type = LightType::Point;
  else if (gl.type == "spot") l.type = LightType::Spot;
  else values.fail(fmt::format("{} has type `{}` (KHR_lights_punctual: directional, point or spot)", what, gl.type));
  l.color = values.lightColor(gl.color, l.color, what + " color");
  l.intensity = values.light(gl.intensity, what + " intensity");
  values.requireLightRange(l.color * l.intensity, what + " (color x intensity)");
  if (gl.range > 0 && std::isfinite(float(gl.range))) l.range = float(gl.range);
  if (l.type == LightType::Spot) {
    l.innerConeAngle = values.finite(gl.spot.innerConeAngle, what + " innerConeAngle");
    l.outerConeAngle = values.finite(gl.spot.outerConeAngle, what + " outerConeAngle");
    if (!(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 0.5f * glm::pi<float>() + 1e-6f))
      values.fail(fmt::format("{} has cone angles inner {} and outer {} (0 <= inner < outer <= pi/2)", what,
                              l.innerConeAngle, l.outerConeAngle));
  }
  l.position = position;
  l.direction = glm::normalize(orientation * glm::dvec3(0.0, 0.0, -1.0));
  if (allFinite(l.direction)) return l;
  values.warn(fmt::format("{} has no direction (its node's transform is singular); it is ignored", what));
  return std::nullopt;
}

// Everything in the file Twinlight does not render (or renders approximately), one entry per
// feature with how often the file uses it: Scene::ignored and one warning each.
class IgnoredFeatures {
 public:
  void add(const std::string& feature, const std::string& instead) {
    for (auto& e : entries_)
      if (e.feature == feature) return void(++e.count);
    entries_.push_back({feature, instead, 1});
  }
  void report(Scene& scene, const std::filesystem::path& file) const {
    for (const auto& e : entries_) {
      std::string line = fmt::format("{} ({}x): {}", e.feature, e.count, e.instead);
      scene.warnings.push_back(fmt::format("{}: {}", file.string(), line));
      scene.ignored.push_back(std::move(line));
    }
  }

 private:
  struct Entry {
    std::string feature, instead;
    size_t count;
  };
  std::vector<Entry> entries_;
};

// The texture slots of a material, with their glTF names.
template <class F>
void forEachTextureSlot(const tinygltf::Material& m, F f) {
  f("baseColorTexture", m.pbrMetallicRoughness.baseColorTexture.index, m.pbrMetallicRoughness.baseColorTexture.texCoord,
    m.pbrMetallicRoughness.baseColorTexture.extensions);
  f("metallicRoughnessTexture", m.pbrMetallicRoughness.metallicRoughnessTexture.index,
    m.pbrMetallicRoughness.metallicRoughnessTexture.texCoord, m.pbrMetallicRoughness.metallicRoughnessTexture.extensions);
  f("normalTexture", m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions);
  f("occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord, m.occlusionTexture.extensions);
  f("emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions);
}

// A material's textureInfo: its texture (through the cache), UV set and KHR_texture_transform
// (whose texCoord overrides the textureInfo's, as the extension says). UV sets beyond
// TEXCOORD_1 read TEXCOORD_0 (IgnoredFeatures says so).
std::optional<TextureRef> textureRef(TextureCache& textures, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                                     bool srgb, ImportValues& values, const std::string& what) {
  const auto texture = textures.get(index, srgb);
  if (!texture) return std::nullopt;
  TextureRef r;
  r.texture = *texture;
  if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
    const auto& t = it->second;
    auto pair = [&](const char* name, glm::vec2& out) {
      if (!t.Has(name)) return;
      const auto& v = t.Get(name);
      if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
        values.fail(fmt::format("{} KHR_texture_transform {} is not two numbers", what, name));
      for (int c = 0; c < 2; ++c) out[c] = values.finite(v.Get(c).GetNumberAsDouble(), fmt::format("{} KHR_texture_transform {}", what, name));
    };
    pair("offset", r.offset);
    pair("scale", r.scale);
    if (t.Has("rotation")) {
      if (!t.Get("rotation").IsNumber()) values.fail(what + " KHR_texture_transform rotation is not a number");
      r.rotation = values.finite(t.Get("rotation").GetNumberAsDouble(), what + " KHR_texture_transform rotation");
    }
    if (t.Has("texCoord") && t.Get("texCoord").IsInt()) texCoord = t.Get("texCoord").GetNumberAsInt();
  }
  r.texCoord = texCoord == 1 ? 1u : 0u;
  return r;
}

void scanIgnored(const tinygltf::Model& model, IgnoredFeatures& ignored) {
  static const std::set<std::string> applied = {"KHR_materials_emissive_strength", "KHR_lights_punctual",
                                                "KHR_mesh_quantization", "KHR_texture_transform"};
  for (const auto& e : model.extensionsUsed)
    if (!applied.count(e)) ignored.add("extension " + e, "not applied (the file renders as if it were absent)");
  for (const auto& m : model.materials) {
    forEachTextureSlot(m, [&](const char* slot, int index, int texCoord, const tinygltf::ExtensionMap& extensions) {
      if (index < 0) return;
      if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end() && it->second.Has("texCoord") &&
                                                               it->second.Get("texCoord").IsInt())
        texCoord = it->second.Get("texCoord").GetNumberAsInt();
      if (texCoord > 1) ignored.add(fmt::format("TEXCOORD_{} in a {}", texCoord, slot), "sampled with TEXCOORD_0");
    });
  }
  for (const auto& mesh : model.meshes)
    for (const auto& p : mesh.primitives) {
      if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) ignored.add("points, lines and strips", "primitives skipped");
      if (p.attributes.count("JOINTS_1") || p.attributes.count("WEIGHTS_1"))
        ignored.add("more than four joints per vertex (JOINTS_1/WEIGHTS_1)", "the first four are used, their weights renormalised");
      if (p.attributes.count("JOINTS_0") != p.attributes.count("WEIGHTS_0"))
        ignored.add("JOINTS_0 without WEIGHTS_0 (or the other way)", "drawn as stored");
      for (const auto& target : p.targets)
        if (target.count("TANGENT")) ignored.add("morph target TANGENT deltas", "tangents keep their rest pose");
    }
  for (const auto& a : model.animations)
    for (const auto& ch : a.channels)
      if (ch.target_path != "weights" && ch.target_path != "translation" && ch.target_path != "rotation" &&
          ch.target_path != "scale")
        ignored.add(fmt::format("node {} animation", ch.target_path), "not played (morph weights and node TRS are)");
  if (model.scenes.size() > 1) ignored.add("scenes besides the default", "not loaded");
}

// An animation sampler's keyframe times: finite and never decreasing, else one error.
std::vector<float> keyTimes(const Reader& rd, const tinygltf::AnimationSampler& sampler, size_t animation) {
  std::vector<float> times;
  for (const auto& t : rd.floats<1>(sampler.input, "animation input")) {
    if (!std::isfinite(t.x) || (!times.empty() && t.x < times.back()))
      rd.fail(fmt::format("animation {} has keyframe times that are not finite and increasing", animation));
    times.push_back(t.x);
  }
  return times;
}

// Whether node `root` or a node below it holds a camera or a light (KHR_lights_punctual).
bool holdsCameraOrLight(const tinygltf::Model& model, int root) {
  std::vector<bool> seen(model.nodes.size(), false);
  std::vector<int> open{root};
  while (!open.empty()) {
    const int n = open.back();
    open.pop_back();
    if (n < 0 || size_t(n) >= model.nodes.size() || seen[size_t(n)]) continue;
    seen[size_t(n)] = true;
    const auto& node = model.nodes[size_t(n)];
    if (node.camera >= 0 || node.extensions.count("KHR_lights_punctual")) return true;
    open.insert(open.end(), node.children.begin(), node.children.end());
  }
  return false;
}

// The file's skins: joints (existing nodes) and inverse bind matrices (finite; identity where
// the file gives none, as glTF says).
void readSkins(const tinygltf::Model& model, const Reader& rd, Scene& scene) {
  for (size_t si = 0; si < model.skins.size(); ++si) {
    const auto& gs = model.skins[si];
    Skin skin;
    skin.name = gs.name.empty() ? fmt::format("skin{}", si) : gs.name;
    for (int j : gs.joints) {
      if (j < 0 || size_t(j) >= model.nodes.size())
        rd.fail(fmt::format("skin `{}` has joint node {}, which does not exist", skin.name, j));
      skin.joints.push_back(uint32_t(j));
    }
    skin.inverseBind.assign(skin.joints.size(), glm::dmat4(1.0));
    if (gs.inverseBindMatrices >= 0) {
      const auto matrices = rd.matrices(gs.inverseBindMatrices, "inverseBindMatrices");
      if (matrices.size() < skin.joints.size())
        rd.fail(fmt::format("skin `{}` has {} inverse bind matrices for {} joints", skin.name, matrices.size(), skin.joints.size()));
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        if (!usableTransform(matrices[j]))
          rd.fail(fmt::format("skin `{}` has a non-finite or out-of-range inverse bind matrix (joint {})", skin.name, j));
        skin.inverseBind[j] = matrices[j];
      }
    }
    scene.skins.push_back(std::move(skin));
  }
}

// Channels of node translation, rotation and scale (glTF 2.0 section 3.11). Each value is
// checked as the double it is stored in: finite, translations and scales within
// InputLimits::kMaxCoordinate, rotations of non-zero length. Scene::bounds grows to hold the
// instances at every key (and halfway between keys, where a rotation swings furthest from both).
void readNodeAnimations(const tinygltf::Model& model, const Reader& rd, ImportValues& values, IgnoredFeatures& ignored,
                        Scene& scene) {
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const auto& anim = model.animations[ai];
    for (const auto& ch : anim.channels) {
      const bool rotation = ch.target_path == "rotation";
      if (ch.target_path != "translation" && !rotation && ch.target_path != "scale") continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        rd.fail(fmt::format("animation {} has a channel with sampler {}, which does not exist", ai, ch.sampler));
      if (ch.target_node < 0) continue;  // glTF: a channel without a node belongs to an extension
      if (size_t(ch.target_node) >= model.nodes.size())
        rd.fail(fmt::format("animation {} drives node {}, which does not exist", ai, ch.target_node));
      const Node& node = scene.nodes[size_t(ch.target_node)];
      if (node.matrix) {
        ignored.add("animation of a node given as a matrix", "not played (glTF animates only nodes given as TRS)");
        continue;
      }
      if (holdsCameraOrLight(model, ch.target_node))
        ignored.add("animation of a camera's or a light's node", "the camera or light stays where the file places it");
      const auto& sampler = anim.samplers[size_t(ch.sampler)];
      NodeAnimation a;
      a.node = uint32_t(ch.target_node);
      a.property = rotation ? NodeProperty::Rotation : ch.target_path == "scale" ? NodeProperty::Scale : NodeProperty::Translation;
      a.interpolation = sampler.interpolation == "STEP"          ? Interpolation::Step
                        : sampler.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                                 : Interpolation::Linear;
      a.times = keyTimes(rd, sampler, ai);
      const size_t perKey = a.interpolation == Interpolation::CubicSpline ? 3 : 1;
      if (rotation) {
        for (const auto& q : rd.floats<4>(sampler.output, "animation output")) a.values.emplace_back(q);
      } else {
        for (const auto& v : rd.floats<3>(sampler.output, "animation output")) a.values.emplace_back(v, 0.0f);
      }
      const std::string what = fmt::format("animation {} {} of node `{}`", ai, ch.target_path, node.name);
      if (a.values.size() != a.times.size() * perKey)
        rd.fail(fmt::format("{} has {} values for {} keys ({} expected)", what, a.values.size(), a.times.size(),
                            a.times.size() * perKey));
      for (size_t k = 0; k < a.values.size(); ++k) {
        const glm::dvec4& v = a.values[k];
        for (int c = 0; c < 4; ++c) values.finite(v[c], what);
        const bool tangent = perKey == 3 && k % 3 != 1;
        if (!rotation && glm::length(glm::dvec3(v)) > InputLimits::kMaxCoordinate)
          rd.fail(fmt::format("{} has a value beyond {:g}", what, InputLimits::kMaxCoordinate));
        if (rotation && !tangent && !(glm::length(v) > 1e-6))
          rd.fail(fmt::format("{} has a rotation of zero length (not a quaternion)", what));
      }
      if (!a.times.empty()) scene.animationSeconds = std::max(scene.animationSeconds, double(a.times.back()));
      scene.nodeAnimations.push_back(std::move(a));
    }
  }
  std::vector<bool> animated(scene.nodes.size(), false);
  for (const auto& a : scene.nodeAnimations) animated[a.node] = true;
  for (const auto& inst : scene.instances) {
    bool moves = false;
    for (int32_t n = int32_t(inst.node); n >= 0 && !moves; n = scene.nodes[size_t(n)].parent) moves = animated[size_t(n)];
    const Material& m = scene.materials[scene.meshes[inst.mesh].material];
    if (moves && (m.emissiveTexture || glm::any(glm::greaterThan(m.emissiveFactor, glm::vec3(0.0f)))))
      ignored.add("an animated emissive mesh", "the rt path samples its light where it rests (the reference and the other paths see it move)");
  }
}

// Bounds that hold every pose the animations make: a skinned mesh's own bounds (object space)
// grow to hold it skinned at each pose, and Scene::bounds to hold every instance at each pose.
// The poses: time 0 and every key of the node channels with the points halfway between (where
// a rotation swings furthest from both), at most kMaxPoses (skinned meshes: kMaxSkinnedPoses,
// each skins every vertex), so a file with many keys costs a bounded import.
void boundAnimatedPoses(const Reader& rd, Scene& scene) {
  bool skinned = false;
  for (const auto& m : scene.meshes) skinned |= m.skinned();
  if (scene.nodeAnimations.empty() && !skinned) return;
  std::vector<double> times{0.0};
  for (const auto& a : scene.nodeAnimations) times.insert(times.end(), a.times.begin(), a.times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  auto posesOf = [&](size_t most) {
    std::vector<double> poses;
    const size_t stride = (times.size() + most - 1) / most;
    for (size_t k = 0; k < times.size(); k += stride) {
      poses.push_back(times[k]);
      if (k + stride < times.size()) poses.push_back(0.5 * (times[k] + times[k + stride]));
    }
    return poses;
  };
  constexpr size_t kMaxPoses = 512, kMaxSkinnedPoses = 64;
  if (skinned) {
    // Morph targets move vertices before skinning: pad each mesh by the most any vertex can move
    // (weights in [-1, 1], as morphBounds assumes).
    std::vector<double> morphReach(scene.meshes.size(), 0.0);
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      for (size_t v = 0; v < scene.meshes[m].vertices.size() && scene.meshes[m].skinned(); ++v) {
        double reach = 0.0;
        for (const MorphTarget& target : scene.meshes[m].morphTargets) reach += glm::length(glm::dvec3(target.positions[v]));
        morphReach[m] = std::max(morphReach[m], reach);
      }
    std::vector<Vertex> posed;
    for (double t : posesOf(kMaxSkinnedPoses)) {
      const std::vector<glm::dmat4> world = nodeWorldTransformsAt(scene, t);
      for (const auto& inst : scene.instances) {
        Mesh& mesh = scene.meshes[inst.mesh];
        if (!mesh.skinned()) continue;
        posed = mesh.vertices;
        skinVertices(mesh, jointMatrices(scene.skins[size_t(mesh.skin)], world[inst.node], world), posed);
        const double pad = morphReach[inst.mesh];
        for (const Vertex& v : posed) {
          mesh.bounds.extend(glm::dvec3(v.position) - pad);
          mesh.bounds.extend(glm::dvec3(v.position) + pad);
        }
        if (!withinWorld(mesh.bounds))
          rd.fail(fmt::format("skin `{}` moves mesh `{}` beyond {:g} m", scene.skins[size_t(mesh.skin)].name, mesh.name,
                              InputLimits::kMaxCoordinate));
      }
    }
    // Between the sampled poses a bone swings on an arc that can reach a little past them:
    // 2% of the mesh's size covers the sag of a 16-degree step (1 - cos 8 degrees ~ 1%).
    for (auto& m : scene.meshes)
      if (m.skinned()) {
        const glm::dvec3 margin(0.02 * std::max({m.bounds.size().x, m.bounds.size().y, m.bounds.size().z}));
        m.bounds.min -= margin;
        m.bounds.max += margin;
      }
    for (auto& inst : scene.instances) inst.worldBounds = transformBounds(scene.meshes[inst.mesh].bounds, inst.transform);
  }
  for (double t : posesOf(kMaxPoses)) {
    const std::vector<glm::dmat4> world = nodeWorldTransformsAt(scene, t);
    for (const auto& inst : scene.instances) {
      const Bounds b = transformBounds(scene.meshes[inst.mesh].bounds, world[inst.node]);
      if (!withinWorld(b))
        rd.fail(fmt::format("an animation moves `{}` beyond {:g} m from the origin", inst.name, InputLimits::kMaxCoordinate));
      scene.bounds.extend(b);
    }
  }
}

}  // namespace

Scene loadGltf(const std::filesystem::path& file, const LoadOptions& options) {
  std::string ext = file.extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = ext == ".glb";
  // Read and measured here, before tinygltf allocates anything for it: a device or a FIFO
  // is refused, and JSON nested deeper than the limit never reaches its recursive parser.
  std::vector<uint8_t> bytes;
  try {
    bytes = readRegularFile(file, binary ? InputLimits::kMaxFileBytes : InputLimits::kMaxGltfJsonBytes);
  } catch (const InputFileError& e) {
    throw SceneError(e.what());
  }
  return loadGltfBytes(std::move(bytes), binary, file, options);
}

Scene loadGltfBytes(std::vector<uint8_t> bytes, bool binary, const std::filesystem::path& file, const LoadOptions& options) {
  try {
    if (bytes.size() > (binary ? InputLimits::kMaxFileBytes : InputLimits::kMaxGltfJsonBytes))
      throw InputFileError(fmt::format("{}: {} bytes, more than a glTF may have", file.string(), bytes.size()));
    requireJsonDepth(jsonText(bytes, binary), file.string());
  } catch (const InputFileError& e) {
    throw SceneError(e.what());
  }

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  loader.SetImageLoader(keepImageBytes, &model);
  BufferAccess access{file, options, {}};
  loader.SetFsCallbacks({fileExists, expandNothing, readBuffer, writeNothing, &access});
  std::string err, warn;
  const std::string baseDir = file.parent_path().string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                             unsigned(bytes.size()), baseDir);
  } catch (const std::exception& e) {
    throw SceneError(fmt::format("{}: not a valid glTF file ({})", file.string(), oneLine(e.what())));
  }
  if (!ok && !access.refusal.empty())
    throw SceneError(fmt::format("{}: a buffer cannot be read: {}", file.string(), oneLine(access.refusal)));
  if (!ok) throw SceneError(fmt::format("{}: not a valid glTF file: {}", file.string(), oneLine(err.empty() ? warn : err)));
  bytes = {};

  // Extensions the importer applies; a file that *requires* any other is refused rather than
  // shown wrongly (merely *used* extensions are ignored, as the glTF specification allows).
  // KHR_mesh_quantization only widens the attribute types, which the accessor reader decodes
  // (normalized and integer components of every size).
  static const std::set<std::string> supported = {"KHR_materials_emissive_strength", "KHR_lights_punctual",
                                                  "KHR_mesh_quantization", "KHR_texture_transform"};
  for (const auto& e : model.extensionsRequired)
    if (!supported.count(e)) throw SceneError(fmt::format("{}: requires the unsupported extension {}", file.string(), e));

  Reader rd(model, file);
  Scene scene;
  scene.name = file.stem().string();
  scene.path = file;
  ImportValues values(file, scene.warnings);
  scene.extensionsUsed = model.extensionsUsed;
  IgnoredFeatures ignored;
  scanIgnored(model, ignored);

  // Textures: one entry per (glTF texture, colour space) actually used by a material.
  TextureCache textures(model, file, options, scene);

  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& gm = model.materials[i];
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name.empty() ? fmt::format("material{}", i) : gm.name;
    const std::string what = fmt::format("material `{}`", m.name);
    // The glTF ranges: factors in [0, 1] (an albedo above 1 creates energy), emission >= 0.
    if (pbr.baseColorFactor.size() == 4)
      for (int c = 0; c < 4; ++c) m.baseColorFactor[c] = values.clamped(pbr.baseColorFactor[size_t(c)], 0.0f, 1.0f, what + " baseColorFactor");
    else if (!pbr.baseColorFactor.empty()) values.fail(what + " baseColorFactor does not have 4 components");
    m.metallic = values.clamped(pbr.metallicFactor, 0.0f, 1.0f, what + " metallicFactor");
    m.roughness = values.clamped(pbr.roughnessFactor, 0.0f, 1.0f, what + " roughnessFactor");
    m.emissiveFactor = values.lightColor(gm.emissiveFactor, m.emissiveFactor, what + " emissiveFactor");
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end()) {
      const auto& s = it->second.Get("emissiveStrength");
      if (s.IsNumber()) m.emissiveStrength = values.light(s.GetNumberAsDouble(), what + " emissiveStrength");
    }
    values.requireLightRange(m.emissiveFactor * m.emissiveStrength, what + " emission (emissiveFactor x emissiveStrength)");
    m.normalScale = values.finite(gm.normalTexture.scale, what + " normalTexture.scale");
    m.alphaMode = gm.alphaMode == "MASK" ? AlphaMode::Mask : gm.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alphaCutoff = values.clamped(gm.alphaCutoff, 0.0f, 1.0f, what + " alphaCutoff");
    m.doubleSided = gm.doubleSided;
    m.baseColorTexture = textureRef(textures, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                    pbr.baseColorTexture.extensions, true, values, what + " baseColorTexture");
    m.metallicRoughnessTexture =
        textureRef(textures, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                   pbr.metallicRoughnessTexture.extensions, false, values, what + " metallicRoughnessTexture");
    m.normalTexture = textureRef(textures, gm.normalTexture.index, gm.normalTexture.texCoord, gm.normalTexture.extensions,
                                 false, values, what + " normalTexture");
    m.emissiveTexture = textureRef(textures, gm.emissiveTexture.index, gm.emissiveTexture.texCoord,
                                   gm.emissiveTexture.extensions, true, values, what + " emissiveTexture");
    m.occlusionTexture = textureRef(textures, gm.occlusionTexture.index, gm.occlusionTexture.texCoord,
                                    gm.occlusionTexture.extensions, false, values, what + " occlusionTexture");
    m.occlusionStrength = values.clamped(gm.occlusionTexture.strength, 0.0f, 1.0f, what + " occlusionTexture.strength");
    scene.materials.push_back(std::move(m));
  }
  const uint32_t defaultMaterial = uint32_t(scene.materials.size());
  bool usedDefault = false;

  // Meshes: one per primitive.
  std::vector<std::vector<uint32_t>> meshPrimitives(model.meshes.size());
  for (size_t mi = 0; mi < model.meshes.size(); ++mi) {
    const auto& gmesh = model.meshes[mi];
    for (size_t pi = 0; pi < gmesh.primitives.size(); ++pi) {
      const auto& prim = gmesh.primitives[pi];
      std::string name = gmesh.name.empty() ? fmt::format("mesh{}", mi) : gmesh.name;
      if (pi > 0) name += fmt::format("#{}", pi);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // IgnoredFeatures says so
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) rd.fail(fmt::format("mesh `{}` primitive {} has no POSITION", name, pi));
      Mesh mesh;
      mesh.name = name;
      auto positions = rd.floats<3>(pos->second, "POSITION");
      mesh.vertices.resize(positions.size());
      for (size_t v = 0; v < positions.size(); ++v) {
        const auto& p = positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          rd.fail(fmt::format("mesh `{}` has a non-finite position (vertex {})", name, v));
        mesh.vertices[v].position = p;
        mesh.bounds.extend(glm::dvec3(p));
      }
      if (prim.indices >= 0) {
        mesh.indices = rd.indices(prim.indices);
      } else {
        mesh.indices.resize(positions.size());
        for (uint32_t v = 0; v < mesh.indices.size(); ++v) mesh.indices[v] = v;
      }
      if (mesh.indices.size() % 3 != 0) rd.fail(fmt::format("mesh `{}` has {} indices, not a multiple of 3", name, mesh.indices.size()));
      for (size_t k = 0; k < mesh.indices.size(); ++k)
        if (mesh.indices[k] >= mesh.vertices.size())
          rd.fail(fmt::format("mesh `{}` index {} is {}, beyond its {} vertices", name, k, mesh.indices[k], mesh.vertices.size()));

      bool haveNormals = false;
      if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        auto normals = rd.floats<3>(it->second, "NORMAL");
        if (normals.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} normals for {} vertices", name, normals.size(), mesh.vertices.size()));
        for (size_t v = 0; v < normals.size(); ++v) mesh.vertices[v].normal = normals[v];
        haveNormals = true;
      }
      if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        auto uvs = rd.floats<2>(it->second, "TEXCOORD_0");
        if (uvs.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} UVs for {} vertices", name, uvs.size(), mesh.vertices.size()));
        for (size_t v = 0; v < uvs.size(); ++v) mesh.vertices[v].uv = uvs[v];
      }
      if (auto it = prim.attributes.find("TEXCOORD_1"); it != prim.attributes.end()) {
        auto uvs = rd.floats<2>(it->second, "TEXCOORD_1");
        if (uvs.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} TEXCOORD_1 for {} vertices", name, uvs.size(), mesh.vertices.size()));
        for (size_t v = 0; v < uvs.size(); ++v) mesh.vertices[v].uv1 = uvs[v];
      }
      if (auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
        // Linear RGB or RGBA as float or normalized integers (glTF 3.7.2.1), multiplied into
        // the base colour; each component is kept to [0, 1] like baseColorFactor.
        const bool rgba = it->second >= 0 && size_t(it->second) < model.accessors.size() &&
                          model.accessors[size_t(it->second)].type == TINYGLTF_TYPE_VEC4;
        std::vector<glm::vec4> colours;
        if (rgba) colours = rd.floats<4>(it->second, "COLOR_0");
        else for (const auto& c : rd.floats<3>(it->second, "COLOR_0")) colours.emplace_back(c, 1.0f);
        if (colours.size() != mesh.vertices.size()) rd.fail(fmt::format("mesh `{}` has {} COLOR_0 for {} vertices", name, colours.size(), mesh.vertices.size()));
        bool clampedAny = false;
        for (size_t v = 0; v < colours.size(); ++v) {
          for (int c = 0; c < 4; ++c)
            if (!std::isfinite(colours[v][c])) rd.fail(fmt::format("mesh `{}` has a non-finite COLOR_0 (vertex {})", name, v));
          const glm::vec4 kept = glm::clamp(colours[v], 0.0f, 1.0f);
          clampedAny |= kept != colours[v];
          mesh.vertices[v].color = kept;
        }
        if (clampedAny) values.warn(fmt::format("mesh `{}` has COLOR_0 components outside [0, 1]; they are clamped", name));
      }
      bool haveTangents = false;
      if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
        auto tangents = rd.floats<4>(it->second, "TANGENT");
        if (tangents.size() == mesh.vertices.size()) {
          for (size_t v = 0; v < tangents.size(); ++v) mesh.vertices[v].tangent = tangents[v];
          haveTangents = true;
        }
      }
      const size_t fileVertices = mesh.vertices.size();
      const std::vector<uint32_t> vertexSource = finishVertices(mesh, haveNormals, haveTangents);
      // Morph targets: displacements of positions (and normals) added with weights.
      for (size_t ti = 0; ti < prim.targets.size(); ++ti) {
        MorphTarget target;
        target.positions.assign(mesh.vertices.size(), glm::vec3(0.0f));
        for (const auto& [attribute, index] : prim.targets[ti]) {
          if (attribute != "POSITION" && attribute != "NORMAL") continue;  // tangent deltas are not applied
          auto deltas = rd.floats<3>(index, "morph target");
          if (deltas.size() != fileVertices)
            rd.fail(fmt::format("mesh `{}` morph target {} has {} {} deltas for {} vertices", name, ti, deltas.size(),
                                attribute, fileVertices));
          for (const auto& d : deltas)
            if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) ||
                std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) > InputLimits::kMaxCoordinate)
              rd.fail(fmt::format("mesh `{}` morph target {} has a non-finite or out-of-range {} delta", name, ti, attribute));
          // Vertices split for their tangents take their original's deltas.
          std::vector<glm::vec3> perVertex(mesh.vertices.size());
          for (size_t k = 0; k < perVertex.size(); ++k) perVertex[k] = deltas[vertexSource[k]];
          (attribute == "POSITION" ? target.positions : target.normals) = std::move(perVertex);
        }
        mesh.morphTargets.push_back(std::move(target));
      }
      // Skinning: four joints and weights per vertex; the node's skin says whose joints they are.
      const auto jointsAttribute = prim.attributes.find("JOINTS_0"), weightsAttribute = prim.attributes.find("WEIGHTS_0");
      if (jointsAttribute != prim.attributes.end() && weightsAttribute != prim.attributes.end()) {
        const auto joints = rd.floats<4>(jointsAttribute->second, "JOINTS_0");
        const auto weights = rd.floats<4>(weightsAttribute->second, "WEIGHTS_0");
        if (joints.size() != fileVertices || weights.size() != fileVertices)
          rd.fail(fmt::format("mesh `{}` has {} JOINTS_0 and {} WEIGHTS_0 for {} vertices", name, joints.size(),
                              weights.size(), fileVertices));
        for (size_t k = 0; k < mesh.vertices.size(); ++k) {
          const size_t v = vertexSource[k];
          glm::vec4 w = weights[v];
          for (int c = 0; c < 4; ++c)
            if (!(w[c] >= 0.0f) || !std::isfinite(w[c]) || !(joints[v][c] >= 0.0f && joints[v][c] <= 65535.0f))
              rd.fail(fmt::format("mesh `{}` vertex {} has a joint or weight that is negative or not finite", name, v));
          const float sum = w.x + w.y + w.z + w.w;
          if (!(sum > 0.0f)) rd.fail(fmt::format("mesh `{}` vertex {} has weights that sum to 0", name, v));
          mesh.joints.push_back(glm::u16vec4(joints[v]));
          mesh.weights.push_back(w / sum);  // glTF asks for a sum of 1; exporters round
        }
      }
      if (!withinWorld(mesh.bounds))
        rd.fail(fmt::format("mesh `{}` has positions beyond {:g} m from its origin", name, InputLimits::kMaxCoordinate));
      if (!mesh.morphTargets.empty()) {
        mesh.morphWeights.assign(mesh.morphTargets.size(), 0.0f);
        for (size_t k = 0; k < gmesh.weights.size() && k < mesh.morphWeights.size(); ++k)
          mesh.morphWeights[k] = values.morphWeight(gmesh.weights[k], fmt::format("mesh `{}` weight {}", name, k));
        mesh.bounds = morphBounds(mesh);
      }
      if (prim.material >= 0 && size_t(prim.material) < scene.materials.size()) {
        mesh.material = uint32_t(prim.material);
      } else {
        mesh.material = defaultMaterial;
        usedDefault = true;
      }
      mesh.contentHash = hashMesh(mesh);
      meshPrimitives[mi].push_back(uint32_t(scene.meshes.size()));
      scene.meshes.push_back(std::move(mesh));
    }
  }
  if (usedDefault || scene.materials.empty()) {
    Material m;
    m.name = "default";
    m.metallic = 0.0f;
    m.roughness = 0.8f;
    m.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    scene.materials.push_back(m);
  }
  for (auto& m : scene.materials) m.contentHash = hashMaterial(m, scene.textures);

  // Node hierarchy -> instances, cameras and lights with world transforms.
  std::vector<bool> meshInstanced(scene.meshes.size(), false);
  std::vector<std::vector<float>> meshDefaultWeights;
  for (const auto& m : scene.meshes) meshDefaultWeights.push_back(m.morphWeights);
  readSkins(model, rd, scene);
  std::vector<bool> visited(model.nodes.size(), false);
  scene.nodes.resize(model.nodes.size());
  for (size_t ni = 0; ni < model.nodes.size(); ++ni) scene.nodes[ni] = localNode(model.nodes[ni], int(ni));
  std::function<void(int, int, const glm::dmat4&, int)> visit = [&](int ni, int parentIndex, const glm::dmat4& parent,
                                                                    int depth) {
    if (ni < 0 || size_t(ni) >= model.nodes.size()) rd.fail(fmt::format("a node refers to node {}, which does not exist", ni));
    if (visited[size_t(ni)] || depth > 1000) rd.fail(fmt::format("node {} appears twice in the hierarchy (a cycle)", ni));
    visited[size_t(ni)] = true;
    scene.nodes[size_t(ni)].parent = parentIndex;
    const auto& node = model.nodes[size_t(ni)];
    glm::dmat4 world = parent * nodeRestTransform(scene.nodes[size_t(ni)]);
    if (!usableTransform(world))
      rd.fail(fmt::format("node {} has a non-finite transform or one placing it beyond {:g} m", ni, InputLimits::kMaxCoordinate));
    std::string nodeName = node.name.empty() ? fmt::format("node{}", ni) : node.name;
    if (node.mesh >= 0 && !invertible(world)) {
      // Nothing to see (a zero scale hides a node), and no normal transform to give it.
      values.warn(fmt::format("node `{}` has a singular transform (a zero scale); its mesh is not drawn", nodeName));
    } else if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model.meshes.size()) rd.fail(fmt::format("node `{}` refers to mesh {}, which does not exist", nodeName, node.mesh));
      const auto& prims = meshPrimitives[size_t(node.mesh)];
      for (size_t k = 0; k < prims.size(); ++k) {
        Instance inst;
        inst.name = prims.size() > 1 ? fmt::format("{}#{}", nodeName, k) : nodeName;
        inst.mesh = prims[k];
        const bool withJoints = !scene.meshes[inst.mesh].joints.empty();
        if (withJoints && node.skin < 0)
          ignored.add("JOINTS_0/WEIGHTS_0 on a node without a skin", "drawn as stored (glTF skins a mesh through its node)");
        if (scene.meshes[inst.mesh].deforms() || (withJoints && node.skin >= 0)) {
          // A deforming mesh follows its node's weights and skin: every further node gets its own copy.
          if (meshInstanced[inst.mesh]) {
            Mesh copy = scene.meshes[inst.mesh];
            copy.name += "@" + nodeName;
            inst.mesh = uint32_t(scene.meshes.size());
            scene.meshes.push_back(std::move(copy));
            meshInstanced.push_back(false);
          }
          Mesh& mesh = scene.meshes[inst.mesh];
          mesh.skin = withJoints ? node.skin : -1;
          if (mesh.skinned()) {
            if (size_t(node.skin) >= scene.skins.size())
              rd.fail(fmt::format("node `{}` refers to skin {}, which does not exist", nodeName, node.skin));
            for (const auto& j : mesh.joints)
              if (std::max({j.x, j.y, j.z, j.w}) >= scene.skins[size_t(node.skin)].joints.size())
                rd.fail(fmt::format("mesh `{}` names joint {} of skin {}, which has {}", mesh.name,
                                    std::max({j.x, j.y, j.z, j.w}), node.skin, scene.skins[size_t(node.skin)].joints.size()));
          }
          // The glTF mesh's own weights, then the node's (an earlier node's never carry over).
          mesh.morphWeights = meshDefaultWeights[prims[k]];
          for (size_t w = 0; w < node.weights.size() && w < mesh.morphWeights.size(); ++w)
            mesh.morphWeights[w] = values.morphWeight(node.weights[w], fmt::format("node `{}` weight {}", nodeName, w));
        }
        meshInstanced[inst.mesh] = true;
        inst.node = uint32_t(ni);
        inst.transform = world;
        inst.worldBounds = transformBounds(scene.meshes[prims[k]].bounds, world);
        if (!withinWorld(inst.worldBounds))
          rd.fail(fmt::format("node `{}` places mesh `{}` beyond {:g} m from the origin", nodeName,
                              scene.meshes[inst.mesh].name, InputLimits::kMaxCoordinate));
        scene.bounds.extend(inst.worldBounds);
        scene.instances.push_back(std::move(inst));
      }
    }
    glm::dvec3 position(world[3]);
    glm::dquat orientation = glm::normalize(glm::quat_cast(glm::dmat3(glm::normalize(glm::dvec3(world[0])),
                                                                      glm::normalize(glm::dvec3(world[1])),
                                                                      glm::normalize(glm::dvec3(world[2])))));
    if (node.camera >= 0 && size_t(node.camera) < model.cameras.size()) {
      const auto& gc = model.cameras[size_t(node.camera)];
      const auto& p = gc.perspective;
      const std::string cameraName = gc.name.empty() ? nodeName : gc.name;
      const auto placed = [&] {  // either kind: the name and where the node puts it
        Camera c;
        c.name = cameraName;
        c.position = position;
        c.orientation = orientation;
        return c;
      };
      // The glTF ranges: 0 < yfov (the session takes up to 178 degrees), 0 < znear < zfar.
      const bool usable = float(p.yfov) > 0.0f && float(p.yfov) < 3.1f && float(p.znear) > 0.0f &&
                          std::isfinite(float(p.znear)) && std::isfinite(float(p.zfar)) &&
                          (p.zfar <= 0.0 || p.zfar > p.znear) && std::isfinite(float(p.aspectRatio)) &&
                          p.aspectRatio >= 0.0 && allFinite(glm::dvec4(orientation.x, orientation.y, orientation.z, orientation.w));
      if (gc.type == "perspective" && !usable) {
        values.warn(fmt::format("camera `{}` has a field of view, clip planes or orientation out of range; it is ignored", cameraName));
      } else if (gc.type == "perspective") {
        Camera c = placed();
        c.yfovRadians = float(p.yfov);
        c.znear = float(p.znear);
        if (p.zfar > 0) c.zfar = float(p.zfar);
        if (p.aspectRatio > 0) c.aspectRatio = float(p.aspectRatio);
        scene.cameras.push_back(c);
      } else if (gc.type == "orthographic") {
        // glTF: xmag and ymag must not be zero (and should not be negative: their size is
        // taken), 0 <= znear < zfar, zfar required.
        const auto& o = gc.orthographic;
        const float xmag = std::abs(float(o.xmag)), ymag = std::abs(float(o.ymag));
        const float znear = float(o.znear), zfar = float(o.zfar);
        const bool orthoUsable = xmag > 0.0f && ymag > 0.0f && std::isfinite(xmag) && std::isfinite(ymag) &&
                                 znear >= 0.0f && std::isfinite(zfar) && zfar > znear &&
                                 allFinite(glm::dvec4(orientation.x, orientation.y, orientation.z, orientation.w));
        if (!orthoUsable) {
          values.warn(fmt::format("orthographic camera `{}` has a magnification or clip planes out of range; it is ignored",
                                  cameraName));
        } else {
          Camera c = placed();
          c.orthographic = true;
          c.xmag = xmag;
          c.ymag = ymag;
          c.znear = znear;
          c.zfar = zfar;
          c.aspectRatio = xmag / ymag;
          scene.cameras.push_back(c);
        }
      }
    }
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const auto& li = it->second.Get("light");
      int index = li.IsInt() ? li.GetNumberAsInt() : -1;
      if (index < 0 || size_t(index) >= model.lights.size())
        values.fail(fmt::format("node `{}` refers to light {}, which does not exist", nodeName, index));
      if (auto l = readLight(model.lights[size_t(index)], nodeName, position, orientation, values)) {
        l->node = uint32_t(ni);
        scene.lights.push_back(*l);
      }
    }
    for (int child : node.children) visit(child, ni, world, depth + 1);
  };
  std::vector<int> roots;
  const size_t sceneIndex =
      model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? size_t(model.defaultScene) : 0;
  if (!model.scenes.empty()) {
    roots = model.scenes[sceneIndex].nodes;
  } else {
    std::vector<bool> isChild(model.nodes.size(), false);
    for (auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
  }
  for (int r : roots) visit(r, -1, glm::dmat4(1.0), 0);

  // Animations: channels of morph weights drive the meshes of their node's instances; channels
  // of translation, rotation and scale move nodes (readNodeAnimations).
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const auto& anim = model.animations[ai];
    for (const auto& ch : anim.channels) {
      if (ch.target_path != "weights") continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        rd.fail(fmt::format("animation {} has a channel with sampler {}, which does not exist", ai, ch.sampler));
      const auto& sampler = anim.samplers[size_t(ch.sampler)];
      const std::vector<float> times = keyTimes(rd, sampler, ai);
      auto outputs = rd.floats<1>(sampler.output, "animation output");
      const bool cubic = sampler.interpolation == "CUBICSPLINE";
      for (const auto& inst : scene.instances) {
        if (int(inst.node) != ch.target_node || scene.meshes[inst.mesh].morphTargets.empty()) continue;
        const size_t targets = scene.meshes[inst.mesh].morphTargets.size();
        const size_t perKey = cubic ? 3 * targets : targets;
        if (outputs.size() != times.size() * perKey)
          rd.fail(fmt::format("animation {} drives {} morph targets of `{}` with {} values for {} keys", ai, targets,
                              inst.name, outputs.size(), times.size()));
        MorphAnimation a;
        a.mesh = inst.mesh;
        a.step = sampler.interpolation == "STEP";
        a.times = times;
        // A cubic spline's keys hold in-tangents, values and out-tangents: its values, linearly.
        for (size_t k = 0; k < times.size(); ++k)
          for (size_t j = 0; j < targets; ++j) 
            a.weights.push_back(values.morphWeight(outputs[k * perKey + (cubic ? targets : 0) + j].x,
                                                   fmt::format("animation {} weight", ai)));
        if (!a.times.empty()) scene.animationSeconds = std::max(scene.animationSeconds, double(a.times.back()));
        scene.morphAnimations.push_back(std::move(a));
      }
    }
  }

  readNodeAnimations(model, rd, values, ignored, scene);
  boundAnimatedPoses(rd, scene);

  // Environment: the first directional light is the sun; the others are shaded from the light table.
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.type != LightType::Directional) continue;
    scene.environment.sunDirection = l.direction;
    scene.environment.sunIrradiance = l.radiometric();
    scene.environment.sunFromFile = true;
    scene.environment.sunLight = i;
    break;
  }
  auto readSky = [&](const tinygltf::Value& extras) {
    if (!extras.IsObject() || !extras.Has("twinlight")) return;
    const auto& t = extras.Get("twinlight");
    const auto& sky = t.Get("sky_radiance");
    if (sky.IsArray() && sky.ArrayLen() == 3) {
      glm::vec3 c;
      for (int k = 0; k < 3; ++k) {
        const auto& v = sky.Get(k);
        if (!v.IsNumber() || v.GetNumberAsDouble() < 0.0) rd.fail("extras.twinlight.sky_radiance must be three non-negative numbers");
        c[k] = values.finite(v.GetNumberAsDouble(), "extras.twinlight.sky_radiance");
      }
      values.requireLightRange(c, "extras.twinlight.sky_radiance");
      scene.environment.skyRadiance = c;
    }
  };
  readSky(model.extras);
  if (!model.scenes.empty()) readSky(model.scenes[sceneIndex].extras);

  ignored.report(scene, file);
  scene.contentHash = hashScene(scene);
  return scene;
}

}  // namespace tl::scene
