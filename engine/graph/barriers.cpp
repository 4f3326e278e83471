#include "graph/barriers.h"

#include <algorithm>

namespace tl::graph {

const char* kindName(PassKind k) {
  switch (k) {
    case PassKind::Raster: return "raster";
    case PassKind::Compute: return "compute";
    case PassKind::RayTracing: return "ray tracing";
    case PassKind::Transfer: return "transfer";
    case PassKind::AccelerationStructureBuild: return "acceleration-structure build";
  }
  return "?";
}

bool isWrite(Usage u) {
  switch (u) {
    case Usage::StorageWrite: case Usage::ColorAttachment: case Usage::DepthAttachment: case Usage::TransferDst:
    case Usage::BuildScratch: case Usage::AccelerationStructureWrite:
      return true;
    default:
      return false;
  }
}

const char* usageName(Usage u) {
  switch (u) {
    case Usage::Sampled: return "Sampled";
    case Usage::StorageRead: return "StorageRead";
    case Usage::DepthRead: return "DepthRead";
    case Usage::TransferSrc: return "TransferSrc";
    case Usage::VertexOrIndex: return "VertexOrIndex";
    case Usage::BuildInput: return "BuildInput";
    case Usage::AccelerationStructureRead: return "AccelerationStructureRead";
    case Usage::StorageWrite: return "StorageWrite";
    case Usage::ColorAttachment: return "ColorAttachment";
    case Usage::DepthAttachment: return "DepthAttachment";
    case Usage::TransferDst: return "TransferDst";
    case Usage::BuildScratch: return "BuildScratch";
    case Usage::AccelerationStructureWrite: return "AccelerationStructureWrite";
  }
  return "?";
}

namespace {

// The shader stages a kind of pass runs; 0 for kinds that run no shaders.
VkPipelineStageFlags2 shaderStages(PassKind kind) {
  switch (kind) {
    case PassKind::Raster: return VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case PassKind::Compute: return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    case PassKind::RayTracing: return VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
    case PassKind::Transfer: case PassKind::AccelerationStructureBuild: return 0;
  }
  return 0;
}

constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;

bool contains(const StageAccess& outer, const StageAccess& inner) {
  return (outer.stages & inner.stages) == inner.stages && (outer.access & inner.access) == inner.access;
}

void addWaiter(std::vector<PassId>& list, PassId pass) {
  if (std::find(list.begin(), list.end(), pass) == list.end()) list.push_back(pass);
}

}  // namespace

bool accessFor(Usage usage, PassKind kind, StageAccess& scope, VkImageLayout& layout) {
  const VkPipelineStageFlags2 shaders = shaderStages(kind);
  const bool raster = kind == PassKind::Raster, build = kind == PassKind::AccelerationStructureBuild;
  const bool commands = kind != PassKind::AccelerationStructureBuild;  // may record copies and clears
  auto set = [&](bool allowed, VkPipelineStageFlags2 s, VkAccessFlags2 a, VkImageLayout l) {
    scope = {s, a};
    layout = l;
    return allowed && s != 0;
  };
  switch (usage) {
    case Usage::Sampled:
      return set(shaders != 0, shaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
    case Usage::StorageRead:
      return set(shaders != 0, shaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL);
    case Usage::StorageWrite:
      return set(shaders != 0, shaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 VK_IMAGE_LAYOUT_GENERAL);
    case Usage::DepthRead:
      return set(raster, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
    case Usage::ColorAttachment:
      return set(raster, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    case Usage::DepthAttachment:
      return set(raster, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    case Usage::VertexOrIndex:
      return set(raster, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT,
                 VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED);
    case Usage::TransferSrc:
      return set(commands, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    case Usage::TransferDst:
      return set(commands, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    case Usage::BuildInput:
      // Vertex, index and instance data of a build are shader reads at the build stage.
      return set(build, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_SHADER_READ_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED);
    case Usage::BuildScratch:
      return set(build, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                 VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                 VK_IMAGE_LAYOUT_UNDEFINED);
    case Usage::AccelerationStructureRead:
      return set(true, build ? VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR : shaders,
                 VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED);
    case Usage::AccelerationStructureWrite:
      return set(build, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                 VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED);
  }
  return false;
}

StageAccess pendingAccesses(const ResourceState& state) {
  StageAccess out;
  if (state.write) out = {state.write->scope.stages, state.write->scope.access & kWriteAccess};
  for (const PastAccess& read : state.reads) out.stages |= read.scope.stages;
  return out;
}

ResourceState carriedOver(const ResourceState& state) {
  ResourceState out;
  out.layout = state.layout;
  if (state.write) out.write = PastAccess{state.write->scope, kNone};
  for (const PastAccess& read : state.reads) {
    const PastAccess earlier{read.scope, kNone};
    if (std::find(out.reads.begin(), out.reads.end(), earlier) == out.reads.end()) out.reads.push_back(earlier);
  }
  return out;
}

std::optional<Barrier> advance(ResourceState& state, ResourceId resource, const PassAccess& access, bool image,
                               PassId pass) {
  Barrier b;
  b.resource = resource;
  b.dst = access.scope;
  if (image) b.oldLayout = state.layout, b.newLayout = access.layout;
  auto waitForWrite = [&] {
    if (!state.write) return;
    b.src.stages |= state.write->scope.stages;
    b.src.access |= state.write->scope.access & kWriteAccess;
    addWaiter(b.waitsFor, state.write->pass);
  };

  // A write, or a layout transition (which rewrites the image), waits for the last write and
  // for every read since: reads need no availability, only to have finished.
  if (access.writes || b.transition()) {
    waitForWrite();
    for (const PastAccess& read : state.reads) {
      b.src.stages |= read.scope.stages;
      addWaiter(b.waitsFor, read.pass);
    }
    const bool needed = b.transition() || b.src.stages != 0;
    if (access.writes) {
      state.write = PastAccess{access.scope, pass};
      state.reads.clear();
    } else {
      // The transition happens before this reader's stages: a later reader elsewhere must
      // chain onto those stages as well as onto the write the transition followed.
      PastAccess w = state.write.value_or(PastAccess{{}, pass});
      w.scope.stages |= access.scope.stages;
      state.write = w;
      state.reads.assign(1, PastAccess{access.scope, pass});
    }
    if (image) state.layout = access.layout;
    return needed ? std::optional<Barrier>(std::move(b)) : std::nullopt;
  }

  // A read in the current layout: it waits for the last write unless a barrier already made
  // that write visible to these stages and accesses.
  const bool synchronised =
      !state.write || std::any_of(state.reads.begin(), state.reads.end(),
                                  [&](const PastAccess& r) { return contains(r.scope, access.scope); });
  const PastAccess read{access.scope, pass};
  if (std::find(state.reads.begin(), state.reads.end(), read) == state.reads.end()) state.reads.push_back(read);
  if (synchronised) return std::nullopt;
  waitForWrite();
  return b;
}

// ---- names for the dump ------------------------------------------------------------------

namespace {

template <class Flags, size_t N>
std::string flagNames(Flags flags, const std::pair<Flags, const char*> (&table)[N], const char* none) {
  std::string out;
  for (const auto& [bit, name] : table) {
    if ((flags & bit) != bit) continue;
    if (!out.empty()) out += '+';
    out += name;
    flags &= ~bit;
  }
  if (flags) out += out.empty() ? "other" : "+other";
  return out.empty() ? none : out;
}

}  // namespace

std::string stageNames(VkPipelineStageFlags2 stages) {
  static const std::pair<VkPipelineStageFlags2, const char*> table[] = {
      {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "all"},
      {VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, "vertex input"},
      {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "vertex"},
      {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "depth tests"},
      {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "early depth test"},
      {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "late depth test"},
      {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "fragment"},
      {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "colour output"},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "compute"},
      {VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, "ray tracing"},
      {VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, "as build"},
      {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "transfer"},
      {VK_PIPELINE_STAGE_2_HOST_BIT, "host"},
  };
  return flagNames(stages, table, "none");
}

std::string accessNames(VkAccessFlags2 access) {
  static const std::pair<VkAccessFlags2, const char*> table[] = {
      {VK_ACCESS_2_MEMORY_READ_BIT, "memory read"},
      {VK_ACCESS_2_MEMORY_WRITE_BIT, "memory write"},
      {VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT, "vertex+index read"},
      {VK_ACCESS_2_UNIFORM_READ_BIT, "uniform read"},
      {VK_ACCESS_2_SHADER_READ_BIT, "shader read"},
      {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "sampled read"},
      {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "storage read"},
      {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "storage write"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "colour read"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "colour write"},
      {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "depth read"},
      {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "depth write"},
      {VK_ACCESS_2_TRANSFER_READ_BIT, "transfer read"},
      {VK_ACCESS_2_TRANSFER_WRITE_BIT, "transfer write"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, "as read"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, "as write"},
      {VK_ACCESS_2_HOST_WRITE_BIT, "host write"},
  };
  return flagNames(access, table, "none");
}

const char* layoutName(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return "READ_ONLY";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL: return "DEPTH_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL: return "DEPTH_READ_ONLY";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST";
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC";
    default: return "other";
  }
}

}  // namespace tl::graph
