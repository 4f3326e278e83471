#include "gpu/acceleration_structure.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <utility>

namespace tl::gpu {
namespace {

struct Totals {
  std::atomic<uint64_t> bottomLevelBuilds{0}, topLevelBuilds{0}, refits{0}, rebuilds{0}, liveBytes{0};
  std::atomic<uint64_t> bottomLevelBuildNs{0};
};
Totals& totals() {
  static Totals t;
  return t;
}

// Counts one bottom-level build made at load time and its host time since `start`.
void countBottomLevelBuild(std::chrono::steady_clock::time_point start) {
  totals().bottomLevelBuilds += 1;
  totals().bottomLevelBuildNs +=
      uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
}

VkDeviceSize scratchAlignment(Device& device) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &as};
  vkGetPhysicalDeviceProperties2(device.physical(), &p);
  return std::max<VkDeviceSize>(as.minAccelerationStructureScratchOffsetAlignment, 1);
}

void createStructure(Device& device, VkAccelerationStructureTypeKHR type, VkDeviceSize size, std::string_view name,
                     Buffer& storage, VkAccelerationStructureKHR& handle, VkDeviceAddress& address) {
  const auto& ext = device.ext();
  storage = Buffer(device, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, MemoryUsage::GpuOnly, name);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = storage.handle();
  ci.size = size;
  ci.type = type;
  TL_VK(ext.createAccelerationStructure(device.handle(), &ci, nullptr, &handle));
  device.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(handle), name);
  VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = handle;
  address = ext.getAccelerationStructureDeviceAddress(device.handle(), &ai);
}

VkAccelerationStructureBuildGeometryInfoKHR buildInfo(VkAccelerationStructureTypeKHR type,
                                                      const VkAccelerationStructureGeometryKHR& geometry, bool compactable,
                                                      bool allowUpdate = false) {
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = type;
  info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
               (compactable ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR : 0) |
               (allowUpdate ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR : 0);
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.geometryCount = 1;
  info.pGeometries = &geometry;
  return info;
}

VkAccelerationStructureBuildSizesInfoKHR buildSizes(Device& device, const VkAccelerationStructureBuildGeometryInfoKHR& info,
                                                    uint32_t primitives) {
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  device.ext().getAccelerationStructureBuildSizes(device.handle(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                                  &primitives, &sizes);
  return sizes;
}

VkDeviceAddress alignedScratch(Device& device, const Buffer& scratch, VkDeviceSize offset = 0) {
  const VkDeviceSize align = scratchAlignment(device);
  return (scratch.address() + offset + align - 1) / align * align;
}

// Sizes, allocates, builds and waits: the shared tail of both levels. With `compact`, the
// result is copied into a structure of its compacted size.
void build(Device& device, VkAccelerationStructureTypeKHR type, const VkAccelerationStructureGeometryKHR& geometry,
           uint32_t primitives, std::string_view name, bool compact, Buffer& storage,
           VkAccelerationStructureKHR& handle, VkDeviceAddress& address, bool allowUpdate = false) {
  TL_CHECK(device.rayTracing().pipeline, "acceleration structure `{}` needs ray tracing: {}", name,
           device.rayTracing().unavailableReason);
  const auto& ext = device.ext();
  VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(type, geometry, compact, allowUpdate);
  VkAccelerationStructureBuildSizesInfoKHR sizes = buildSizes(device, info, primitives);
  createStructure(device, type, sizes.accelerationStructureSize, name, storage, handle, address);

  Buffer scratch(device, sizes.buildScratchSize + scratchAlignment(device), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 MemoryUsage::GpuOnly, fmt::format("{}.scratch", name));
  info.dstAccelerationStructure = handle;
  info.scratchData.deviceAddress = alignedScratch(device, scratch);
  VkAccelerationStructureBuildRangeInfoKHR range{primitives, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  VkQueryPool pool = VK_NULL_HANDLE;
  if (compact) {
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR;
    qi.queryCount = 1;
    TL_VK(vkCreateQueryPool(device.handle(), &qi, nullptr, &pool));
  }
  device.immediate([&](VkCommandBuffer cmd) {
    ext.cmdBuildAccelerationStructures(cmd, 1, &info, &ranges);
    if (!compact) return;
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    b.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &b, 0, nullptr, 0, nullptr);
    vkCmdResetQueryPool(cmd, pool, 0, 1);
    ext.cmdWriteAccelerationStructuresProperties(cmd, 1, &handle, VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
                                                 pool, 0);
  });
  if (!compact) return;
  VkDeviceSize compacted = 0;
  TL_VK(vkGetQueryPoolResults(device.handle(), pool, 0, 1, sizeof(compacted), &compacted, sizeof(compacted),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  vkDestroyQueryPool(device.handle(), pool, nullptr);
  if (compacted == 0 || compacted >= storage.size()) return;

  Buffer small;
  VkAccelerationStructureKHR smallHandle = VK_NULL_HANDLE;
  VkDeviceAddress smallAddress = 0;
  createStructure(device, type, compacted, name, small, smallHandle, smallAddress);
  device.immediate([&](VkCommandBuffer cmd) {
    VkCopyAccelerationStructureInfoKHR copy{VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR};
    copy.src = handle;
    copy.dst = smallHandle;
    copy.mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR;
    ext.cmdCopyAccelerationStructure(cmd, &copy);
  });
  VkAccelerationStructureKHR old = handle;
  device.destroyLater([&device, old] { device.ext().destroyAccelerationStructure(device.handle(), old, nullptr); });
  storage = std::move(small);
  handle = smallHandle;
  address = smallAddress;
}

VkAccelerationStructureGeometryKHR instancesGeometry(VkDeviceAddress instances) {
  VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geometry.geometry.instances.data.deviceAddress = instances;
  return geometry;
}

std::vector<VkAccelerationStructureInstanceKHR> rawInstances(const std::vector<TlasInstance>& instances) {
  std::vector<VkAccelerationStructureInstanceKHR> raw(instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    const auto& in = instances[i];
    VkAccelerationStructureInstanceKHR& r = raw[i];
    glm::mat4 rowMajor = glm::transpose(in.transform);  // Vulkan wants a row-major 3x4
    std::memcpy(&r.transform, &rowMajor, sizeof(r.transform));
    r.instanceCustomIndex = in.customIndex & 0xFFFFFF;
    r.mask = in.mask;
    r.instanceShaderBindingTableRecordOffset = 0;
    r.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    r.accelerationStructureReference = in.blas;
  }
  return raw;
}

}  // namespace

AccelerationStructureTotals accelerationStructureTotals() {
  const Totals& t = totals();
  AccelerationStructureTotals out;
  out.bottomLevelBuilds = t.bottomLevelBuilds.load();
  out.bottomLevelBuildMs = double(t.bottomLevelBuildNs.load()) * 1e-6;
  out.topLevelBuilds = t.topLevelBuilds.load();
  out.refits = t.refits.load();
  out.rebuilds = t.rebuilds.load();
  out.liveBytes = t.liveBytes.load();
  return out;
}

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
    buffer_ = std::move(o.buffer_);
    address_ = std::exchange(o.address_, 0);
    bytes_ = std::exchange(o.bytes_, 0);
  }
  return *this;
}

void AccelerationStructure::reset() {
  if (handle_) {
    Device* d = device_;
    VkAccelerationStructureKHR h = handle_;
    d->destroyLater([d, h] { d->ext().destroyAccelerationStructure(d->handle(), h, nullptr); });
    totals().liveBytes -= bytes_;
  }
  handle_ = VK_NULL_HANDLE;
  buffer_.reset();
  address_ = 0;
  bytes_ = 0;
}

VkAccelerationStructureGeometryKHR trianglesGeometry(const TriangleGeometry& g) {
  VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  // Non-opaque geometry runs any-hit shaders once per crossing: the reference's shadow rays
  // multiply a pane's transmittance in there, which a repeated call would apply twice.
  geometry.flags = g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR;
  auto& t = geometry.geometry.triangles;
  t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  t.vertexData.deviceAddress = g.vertices;
  t.vertexStride = g.vertexStride;
  t.maxVertex = g.vertexCount ? g.vertexCount - 1 : 0;
  t.indexType = VK_INDEX_TYPE_UINT32;
  t.indexData.deviceAddress = g.indices;
  return geometry;
}

AccelerationStructure buildBottomLevel(Device& device, const TriangleGeometry& g, std::string_view name, bool compact,
                                       bool allowUpdate) {
  const auto start = std::chrono::steady_clock::now();
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  AccelerationStructure as;
  as.device_ = &device;
  build(device, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, g.triangleCount, name,
        compact && !allowUpdate, as.buffer_, as.handle_, as.address_, allowUpdate);
  as.bytes_ = as.buffer_.size();
  totals().liveBytes += as.bytes_;
  countBottomLevelBuild(start);
  return as;
}

VkDeviceSize bottomLevelBytes(Device& device, const TriangleGeometry& g, bool allowUpdate) {
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info =
      buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false, allowUpdate);
  return (buildSizes(device, info, g.triangleCount).accelerationStructureSize + 255) / 256 * 256;
}

AccelerationStructure buildBottomLevelAt(Device& device, const TriangleGeometry& g, std::string_view name,
                                         const Buffer& storage, VkDeviceSize offset, bool allowUpdate) {
  const auto start = std::chrono::steady_clock::now();
  const auto& ext = device.ext();
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info =
      buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false, allowUpdate);
  VkAccelerationStructureBuildSizesInfoKHR sizes = buildSizes(device, info, g.triangleCount);
  TL_CHECK(offset % 256 == 0 && offset + sizes.accelerationStructureSize <= storage.size(),
           "bottom level `{}` does not fit its place in `{}`", name, storage.name());
  AccelerationStructure as;
  as.device_ = &device;
  as.bytes_ = sizes.accelerationStructureSize;
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = storage.handle();
  ci.offset = offset;
  ci.size = sizes.accelerationStructureSize;
  ci.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  TL_VK(ext.createAccelerationStructure(device.handle(), &ci, nullptr, &as.handle_));
  device.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(as.handle_), name);
  VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = as.handle_;
  as.address_ = ext.getAccelerationStructureDeviceAddress(device.handle(), &ai);
  Buffer scratch(device, sizes.buildScratchSize + scratchAlignment(device), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 MemoryUsage::GpuOnly, fmt::format("{}.scratch", name));
  info.dstAccelerationStructure = as.handle_;
  info.scratchData.deviceAddress = alignedScratch(device, scratch);
  VkAccelerationStructureBuildRangeInfoKHR range{g.triangleCount, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device.immediate([&](VkCommandBuffer cmd) { ext.cmdBuildAccelerationStructures(cmd, 1, &info, &ranges); });
  totals().liveBytes += as.bytes_;
  countBottomLevelBuild(start);
  return as;
}

VkDeviceSize refitScratchBytes(Device& device, const TriangleGeometry& g) {
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info =
      buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false, true);
  return buildSizes(device, info, g.triangleCount).updateScratchSize + scratchAlignment(device);
}

VkDeviceSize rebuildScratchBytes(Device& device, const TriangleGeometry& g) {
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false);
  return buildSizes(device, info, g.triangleCount).buildScratchSize + scratchAlignment(device);
}

void recordRefit(VkCommandBuffer cmd, Device& device, const AccelerationStructure& blas, const TriangleGeometry& g,
                 const Buffer& scratch, VkDeviceSize scratchOffset) {
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info =
      buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false, true);
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR;
  totals().refits += 1;
  info.srcAccelerationStructure = blas.handle();
  info.dstAccelerationStructure = blas.handle();
  info.scratchData.deviceAddress = alignedScratch(device, scratch, scratchOffset);
  VkAccelerationStructureBuildRangeInfoKHR range{g.triangleCount, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device.ext().cmdBuildAccelerationStructures(cmd, 1, &info, &ranges);
}

void recordRebuild(VkCommandBuffer cmd, Device& device, const AccelerationStructure& blas, const TriangleGeometry& g,
                   const Buffer& scratch, VkDeviceSize scratchOffset) {
  VkAccelerationStructureGeometryKHR geometry = trianglesGeometry(g);
  VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, false);
  totals().rebuilds += 1;
  info.dstAccelerationStructure = blas.handle();
  info.scratchData.deviceAddress = alignedScratch(device, scratch, scratchOffset);
  VkAccelerationStructureBuildRangeInfoKHR range{g.triangleCount, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device.ext().cmdBuildAccelerationStructures(cmd, 1, &info, &ranges);
}

AccelerationStructure buildTopLevel(Device& device, const std::vector<TlasInstance>& instances, std::string_view name) {
  std::vector<VkAccelerationStructureInstanceKHR> raw = rawInstances(instances);
  Buffer instanceBuffer(device, std::max<size_t>(1, raw.size()) * sizeof(VkAccelerationStructureInstanceKHR),
                        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR, MemoryUsage::Upload,
                        fmt::format("{}.instances", name));
  if (!raw.empty()) instanceBuffer.write(raw.data(), raw.size() * sizeof(raw[0]));
  VkAccelerationStructureGeometryKHR geometry = instancesGeometry(instanceBuffer.address());
  AccelerationStructure as;
  as.device_ = &device;
  build(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry, uint32_t(raw.size()), name, false, as.buffer_,
        as.handle_, as.address_);
  as.bytes_ = as.buffer_.size();
  totals().liveBytes += as.bytes_;
  totals().topLevelBuilds += 1;
  return as;
}

void TopLevelBuilder::prepare(const std::vector<TlasInstance>& instances, uint64_t frame) {
  Device& device = *device_;
  TL_CHECK(device.rayTracing().pipeline, "acceleration structure `{}` needs ray tracing: {}", name_,
           device.rayTracing().unavailableReason);
  count_ = uint32_t(instances.size());
  if (count_ > capacity_ || !structure_) {
    capacity_ = std::max({count_, 2 * capacity_, 64u});
    instances_ = UploadRing(device, capacity_ * sizeof(VkAccelerationStructureInstanceKHR),
                            VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR,
                            fmt::format("{}.instances", name_));
    VkAccelerationStructureGeometryKHR geometry = instancesGeometry(instances_.forFrame(frame).address());
    VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry, false);
    VkAccelerationStructureBuildSizesInfoKHR sizes = buildSizes(device, info, capacity_);
    structure_.reset();
    structure_.device_ = &device;
    createStructure(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, sizes.accelerationStructureSize, name_,
                    structure_.buffer_, structure_.handle_, structure_.address_);
    structure_.bytes_ = structure_.buffer_.size();
    totals().liveBytes += structure_.bytes_;
    scratchBytes_ = sizes.buildScratchSize + scratchAlignment(device);
  }
  std::vector<VkAccelerationStructureInstanceKHR> raw = rawInstances(instances);
  frame_ = frame;
  if (!raw.empty()) instances_.write(frame, raw.data(), raw.size() * sizeof(raw[0]));
}

void TopLevelBuilder::record(VkCommandBuffer cmd, const Buffer& scratch) {
  TL_CHECK(scratch.size() >= scratchBytes_, "`{}` needs {} bytes of build scratch, `{}` has {}", name_, scratchBytes_,
           scratch.name(), scratch.size());
  VkAccelerationStructureGeometryKHR geometry = instancesGeometry(instances_.forFrame(frame_).address());
  VkAccelerationStructureBuildGeometryInfoKHR info = buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry, false);
  info.dstAccelerationStructure = structure_.handle_;
  info.scratchData.deviceAddress = alignedScratch(*device_, scratch);
  VkAccelerationStructureBuildRangeInfoKHR range{count_, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device_->ext().cmdBuildAccelerationStructures(cmd, 1, &info, &ranges);
  totals().topLevelBuilds += 1;
}

}  // namespace tl::gpu
