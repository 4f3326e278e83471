// RAII buffers, images, memory blocks and samplers. Destruction is deferred through
// Device::destroyLater until the GPU has finished with them, so an object can be dropped
// at any point of recording. Every object is created with its debug name.
#pragma once

#include "gpu/device.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tl::gpu {

enum class MemoryUsage : uint8_t { GpuOnly, Upload, Readback };

// A block of device memory that several images may alias (the graph's transient heap).
class Memory {
 public:
  Memory() = default;
  Memory(Device& device, const VkMemoryRequirements& req, MemoryUsage usage, std::string_view name);
  ~Memory() { reset(); }
  Memory(Memory&& o) noexcept { *this = std::move(o); }
  Memory& operator=(Memory&& o) noexcept;
  void reset();
  VkDeviceMemory handle() const { return memory_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }
  explicit operator bool() const { return memory_ != VK_NULL_HANDLE; }

 private:
  Device* device_ = nullptr;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  uint32_t memoryType_ = 0;
  void* mapped_ = nullptr;
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, std::string_view name);
  ~Buffer() { reset(); }
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  void reset();

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  void* mapped() const { return memory_.mapped(); }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

  // Host-visible buffers only.
  void write(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

 private:
  Device* device_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Memory memory_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  std::string name_;
};

struct ImageInfo {
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{1, 1, 1};  // depth > 1: a 3D image
  uint32_t mipLevels = 1;
  VkImageUsageFlags usage = 0;
};

class Image {
 public:
  Image() = default;
  // Own memory.
  Image(Device& device, const ImageInfo& info, std::string_view name);
  // Placed in `memory` at `offset` (aliasing); the caller keeps the memory alive.
  Image(Device& device, const ImageInfo& info, VkDeviceMemory memory, VkDeviceSize offset, std::string_view name);
  ~Image() { reset(); }
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  void reset();

  // Memory requirements of an image with this info, without creating one for good.
  static VkMemoryRequirements requirements(Device& device, const ImageInfo& info);

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }        // all mips
  VkImageView mipView(uint32_t level) const { return mipViews_.at(level); }
  const ImageInfo& info() const { return info_; }
  VkFormat format() const { return info_.format; }
  VkExtent3D extent() const { return info_.extent; }
  VkImageAspectFlags aspect() const;
  bool is3D() const { return info_.extent.depth > 1; }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void create(Device& device, const ImageInfo& info, std::string_view name);
  void createViews();

  Device* device_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> mipViews_;
  Memory ownMemory_;
  ImageInfo info_;
  std::string name_;
};

class Sampler {
 public:
  Sampler() = default;
  Sampler(Device& device, VkFilter filter, VkSamplerAddressMode address, std::string_view name,
          bool compareDepth = false, float maxAnisotropy = 1.0f);
  // Any sampler (per-axis wrap, separate filters): the scene's glTF samplers.
  Sampler(Device& device, const VkSamplerCreateInfo& info, std::string_view name);
  ~Sampler() { reset(); }
  Sampler(Sampler&& o) noexcept { *this = std::move(o); }
  Sampler& operator=(Sampler&& o) noexcept;
  void reset();
  VkSampler handle() const { return sampler_; }

 private:
  Device* device_ = nullptr;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

bool isDepthFormat(VkFormat format);

// One-shot transfers through a staging buffer (wait for completion).
void uploadBuffer(Device& device, Buffer& dst, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
// Uploads mip 0 of a 2D image and leaves it in SHADER_READ_ONLY_OPTIMAL.
void uploadImage2D(Device& device, Image& dst, const void* texels, VkDeviceSize bytes);
// Copies a whole image (mip 0, current `layout`, left in that layout) into host memory.
std::vector<uint8_t> readbackImage(Device& device, const Image& image, VkImageLayout layout);

// Records a layout transition with synchronization2 and broad stages (all commands before
// against all after): for uploads, read-backs and the editor's swapchain, not for passes.
void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                     uint32_t baseMip = 0, uint32_t mipCount = VK_REMAINING_MIP_LEVELS);
void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to);

// A global memory dependency (synchronization2), e.g. between dispatches inside one pass.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// Copies mip 0 of `src` (TRANSFER_SRC_OPTIMAL) into `dst` (TRANSFER_DST_OPTIMAL), same size and aspect.
void copyImage(VkCommandBuffer cmd, const Image& src, const Image& dst);
// Blits mip 0 of `src` (TRANSFER_SRC_OPTIMAL) over mip 0 of `dst` (TRANSFER_DST_OPTIMAL), colour
// images of any formats the blit converts between, nearest texels.
void blitImage(VkCommandBuffer cmd, const Image& src, const Image& dst);
// Clears mip 0 of a colour image to zero in `layout` (GENERAL or TRANSFER_DST_OPTIMAL).
void clearImage(VkCommandBuffer cmd, const Image& image, VkImageLayout layout);

}  // namespace tl::gpu

namespace tl::gpu {
// Uploads mip 0 of a 2D image, builds the rest of its mip chain with linear blits, and
// leaves it in SHADER_READ_ONLY_OPTIMAL.
void uploadImage2DWithMips(Device& device, Image& dst, const void* texels, VkDeviceSize bytes);
inline uint32_t mipCount(uint32_t w, uint32_t h) {
  uint32_t n = 1;
  while ((w | h) >> n) ++n;
  return n;
}
}  // namespace tl::gpu
