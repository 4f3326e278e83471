// Reads a glTF file's accessors (tinygltf leaves them unchecked): every element is checked to
// lie inside its buffer with overflow-safe arithmetic, sparse accessors are applied, and any
// fault is one SceneError naming the file and the accessor.
#pragma once

#include "scene/scene.h"

#include <tiny_gltf.h>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace tl::scene {

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& m, const std::filesystem::path& file) : m_(m), file_(file) {}

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

}  // namespace tl::scene
