#include "gpu/spirv_reflect.h"

#include "gpu/check.h"

#include <map>

namespace tl::gpu {

namespace {
// Opcodes and enumerants of the SPIR-V specification that the reader needs.
enum : uint32_t {
  kOpName = 5, kOpTypeImage = 25, kOpTypeSampler = 26, kOpTypeSampledImage = 27, kOpTypeArray = 28,
  kOpTypeRuntimeArray = 29, kOpTypeStruct = 30, kOpTypePointer = 32, kOpVariable = 59, kOpDecorate = 71,
  kOpTypeAccelerationStructure = 5341,
};
enum : uint32_t { kDecorationBlock = 2, kDecorationBufferBlock = 3, kDecorationBinding = 33, kDecorationSet = 34 };
enum : uint32_t { kStorageUniform = 2, kStorageBuffer = 12 };

std::string literalString(const uint32_t* words, uint32_t count) {
  std::string s;
  for (uint32_t i = 0; i < count; ++i)
    for (int b = 0; b < 4; ++b) {
      const char c = char((words[i] >> (8 * b)) & 0xffu);
      if (c == 0) return s;
      s += c;
    }
  return s;
}
}  // namespace

std::vector<ReflectedBinding> reflectSet0(const std::vector<uint32_t>& spirv) {
  if (spirv.size() < 5 || spirv[0] != 0x07230203u) throw Error("not a SPIR-V module (bad magic)");
  struct Type {
    uint32_t op = 0;
    std::vector<uint32_t> operands;  // after the result id
  };
  std::map<uint32_t, Type> types;
  std::map<uint32_t, std::string> names;
  std::map<uint32_t, uint32_t> binding, set;
  std::map<uint32_t, uint32_t> blockKind;  // struct id -> Block / BufferBlock
  struct Variable {
    uint32_t id, pointerType, storage;
  };
  std::vector<Variable> variables;
  for (size_t at = 5; at < spirv.size();) {
    const uint32_t count = spirv[at] >> 16, op = spirv[at] & 0xffffu;
    if (count == 0 || at + count > spirv.size()) throw Error("SPIR-V module ends inside an instruction");
    const uint32_t* w = &spirv[at];
    if (op == kOpName && count >= 3) names[w[1]] = literalString(w + 2, count - 2);
    if (op == kOpDecorate && count >= 3) {
      if (w[2] == kDecorationBinding && count >= 4) binding[w[1]] = w[3];
      if (w[2] == kDecorationSet && count >= 4) set[w[1]] = w[3];
      if (w[2] == kDecorationBlock || w[2] == kDecorationBufferBlock) blockKind[w[1]] = w[2];
    }
    if ((op >= kOpTypeImage && op <= kOpTypePointer) || op == kOpTypeAccelerationStructure)
      types[w[1]] = Type{op, std::vector<uint32_t>(w + 2, w + count)};
    if (op == kOpVariable && count >= 4) variables.push_back({w[2], w[1], w[3]});
    at += count;
  }
  auto typeOf = [&](uint32_t id) -> const Type* {
    auto it = types.find(id);
    return it == types.end() ? nullptr : &it->second;
  };
  std::vector<ReflectedBinding> out;
  for (const Variable& v : variables) {
    if (!binding.count(v.id) || (set.count(v.id) ? set[v.id] : 0u) != 0) continue;
    const Type* pointer = typeOf(v.pointerType);
    if (!pointer || pointer->op != kOpTypePointer || pointer->operands.size() < 2) continue;
    uint32_t pointee = pointer->operands[1];
    const Type* t = typeOf(pointee);
    while (t && (t->op == kOpTypeArray || t->op == kOpTypeRuntimeArray)) t = typeOf(pointee = t->operands[0]);
    ReflectedBinding r{binding[v.id], VK_DESCRIPTOR_TYPE_MAX_ENUM, names.count(v.id) ? names[v.id] : std::string()};
    if (r.name.empty() && names.count(pointee)) r.name = names[pointee];
    if (t && t->op == kOpTypeSampledImage) r.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (t && t->op == kOpTypeSampler) r.type = VK_DESCRIPTOR_TYPE_SAMPLER;
    if (t && t->op == kOpTypeImage && t->operands.size() >= 6)
      r.type = t->operands[5] == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    if (t && t->op == kOpTypeAccelerationStructure) r.type = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    if (t && t->op == kOpTypeStruct) {
      const bool bufferBlock = blockKind.count(pointee) && blockKind[pointee] == kDecorationBufferBlock;
      if (v.storage == kStorageBuffer || (v.storage == kStorageUniform && bufferBlock))
        r.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      else if (v.storage == kStorageUniform)
        r.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace tl::gpu
