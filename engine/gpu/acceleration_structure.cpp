#include "gpu/acceleration_structure.h"

#include <fmt/format.h>

#include <cstring>
#include <utility>

namespace tl::gpu {
namespace {

VkDeviceSize scratchAlignment(Device& device) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &as};
  vkGetPhysicalDeviceProperties2(device.physical(), &p);
  return std::max<VkDeviceSize>(as.minAccelerationStructureScratchOffsetAlignment, 1);
}

// Sizes, allocates, builds and waits: the shared tail of both levels.
void build(Device& device, VkAccelerationStructureTypeKHR type,
                            const VkAccelerationStructureGeometryKHR& geometry, uint32_t primitives, std::string_view name,
                            Buffer& storage, VkAccelerationStructureKHR& handle, VkDeviceAddress& address) {
  TL_CHECK(device.rayTracing().pipeline, "acceleration structure `{}` needs ray tracing: {}", name,
           device.rayTracing().unavailableReason);
  const auto& ext = device.ext();
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = type;
  info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.geometryCount = 1;
  info.pGeometries = &geometry;
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ext.getAccelerationStructureBuildSizes(device.handle(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &primitives,
                                         &sizes);
  storage = Buffer(device, sizes.accelerationStructureSize, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR,
                   MemoryUsage::GpuOnly, name);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = storage.handle();
  ci.size = sizes.accelerationStructureSize;
  ci.type = type;
  TL_VK(ext.createAccelerationStructure(device.handle(), &ci, nullptr, &handle));
  device.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(handle), name);

  const VkDeviceSize align = scratchAlignment(device);
  Buffer scratch(device, sizes.buildScratchSize + align, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly,
                 fmt::format("{}.scratch", name));
  info.dstAccelerationStructure = handle;
  info.scratchData.deviceAddress = (scratch.address() + align - 1) / align * align;
  VkAccelerationStructureBuildRangeInfoKHR range{primitives, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device.immediate([&](VkCommandBuffer cmd) { ext.cmdBuildAccelerationStructures(cmd, 1, &info, &ranges); });

  VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = handle;
  address = ext.getAccelerationStructureDeviceAddress(device.handle(), &ai);
}

}  // namespace

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
    buffer_ = std::move(o.buffer_);
    address_ = std::exchange(o.address_, 0);
  }
  return *this;
}

void AccelerationStructure::reset() {
  if (handle_) {
    Device* d = device_;
    VkAccelerationStructureKHR h = handle_;
    d->destroyLater([d, h] { d->ext().destroyAccelerationStructure(d->handle(), h, nullptr); });
  }
  handle_ = VK_NULL_HANDLE;
  buffer_.reset();
  address_ = 0;
}

AccelerationStructure buildBottomLevel(Device& device, const TriangleGeometry& g, std::string_view name) {
  VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  geometry.flags = g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : 0;
  auto& t = geometry.geometry.triangles;
  t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  t.vertexData.deviceAddress = g.vertices;
  t.vertexStride = g.vertexStride;
  t.maxVertex = g.vertexCount ? g.vertexCount - 1 : 0;
  t.indexType = VK_INDEX_TYPE_UINT32;
  t.indexData.deviceAddress = g.indices;
  AccelerationStructure as;
  as.device_ = &device;
  build(device, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry, g.triangleCount, name, as.buffer_, as.handle_,
        as.address_);
  return as;
}

AccelerationStructure buildTopLevel(Device& device, const std::vector<TlasInstance>& instances, std::string_view name) {
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
  Buffer instanceBuffer(device, std::max<size_t>(1, raw.size()) * sizeof(VkAccelerationStructureInstanceKHR),
                        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR, MemoryUsage::Upload,
                        fmt::format("{}.instances", name));
  if (!raw.empty()) instanceBuffer.write(raw.data(), raw.size() * sizeof(raw[0]));
  VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geometry.geometry.instances.data.deviceAddress = instanceBuffer.address();
  AccelerationStructure as;
  as.device_ = &device;
  build(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry, uint32_t(raw.size()), name, as.buffer_, as.handle_,
        as.address_);
  return as;
}

}  // namespace tl::gpu
