#include "gpu/resources.h"

#include <fmt/format.h>

#include <cstring>
#include <utility>

namespace tl::gpu {

// ---- Memory ----------------------------------------------------------------------------

Memory::Memory(Device& device, const VkMemoryRequirements& req, MemoryUsage usage, std::string_view name)
    : device_(&device), size_(req.size) {
  VkMemoryPropertyFlags required = usage == MemoryUsage::GpuOnly ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                                                 : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VkMemoryPropertyFlags preferred = usage == MemoryUsage::Readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0;
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = device.findMemoryType(req.memoryTypeBits, required, preferred);
  device.reserveMemory(ai.memoryTypeIndex, req.size, name);
  VkResult r = vkAllocateMemory(device.handle(), &ai, nullptr, &memory_);
  if (r != VK_SUCCESS) device.releaseMemory(ai.memoryTypeIndex, req.size);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    throw Error(fmt::format("out of GPU memory allocating {} bytes for `{}`", req.size, name));
  TL_VK(r);
  memoryType_ = ai.memoryTypeIndex;
  device.setName(VK_OBJECT_TYPE_DEVICE_MEMORY, uint64_t(memory_), name);
  if (usage != MemoryUsage::GpuOnly) TL_VK(vkMapMemory(device.handle(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

Memory& Memory::operator=(Memory&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(o.size_, 0);
    memoryType_ = o.memoryType_;
    mapped_ = std::exchange(o.mapped_, nullptr);
  }
  return *this;
}

void Memory::reset() {
  if (memory_) {
    Device* device = device_;
    VkDeviceMemory m = memory_;
    const uint32_t type = memoryType_;
    const VkDeviceSize size = size_;
    device_->destroyLater([device, m, type, size] {
      vkFreeMemory(device->handle(), m, nullptr);
      device->releaseMemory(type, size);
    });
  }
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  size_ = 0;
}

// ---- Buffer ----------------------------------------------------------------------------

Buffer::Buffer(Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, std::string_view name)
    : device_(&device), size_(size), name_(name) {
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = std::max<VkDeviceSize>(size, 4);
  ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
             VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  TL_VK(vkCreateBuffer(device.handle(), &ci, nullptr, &buffer_));
  device.setName(VK_OBJECT_TYPE_BUFFER, uint64_t(buffer_), name);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device.handle(), buffer_, &req);
  memory_ = Memory(device, req, memory, name);
  TL_VK(vkBindBufferMemory(device.handle(), buffer_, memory_.handle(), 0));
  VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  ai.buffer = buffer_;
  address_ = vkGetBufferDeviceAddress(device.handle(), &ai);
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    memory_ = std::move(o.memory_);
    size_ = std::exchange(o.size_, 0);
    address_ = std::exchange(o.address_, 0);
    name_ = std::move(o.name_);
  }
  return *this;
}

void Buffer::reset() {
  if (buffer_) {
    VkDevice d = device_->handle();
    VkBuffer b = buffer_;
    device_->destroyLater([d, b] { vkDestroyBuffer(d, b, nullptr); });
  }
  buffer_ = VK_NULL_HANDLE;
  memory_.reset();
}

void Buffer::write(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  TL_CHECK(mapped(), "buffer `{}` is not host-visible", name_);
  TL_CHECK(offset + bytes <= size_, "write of {} bytes at {} overflows buffer `{}` ({} bytes)", bytes, offset, name_, size_);
  std::memcpy(static_cast<uint8_t*>(mapped()) + offset, data, bytes);
}

// ---- Image -----------------------------------------------------------------------------

bool isDepthFormat(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D24_UNORM_S8_UINT ||
         f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

namespace {
VkImageCreateInfo imageCreateInfo(const ImageInfo& info) {
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = info.extent.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ci.format = info.format;
  ci.extent = info.extent;
  ci.mipLevels = info.mipLevels;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  // Every image can be copied out: that is what makes read-back of any resource by name work.
  ci.usage = info.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return ci;
}
}  // namespace

VkMemoryRequirements Image::requirements(Device& device, const ImageInfo& info) {
  VkImageCreateInfo ci = imageCreateInfo(info);
  VkDeviceImageMemoryRequirements q{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
  q.pCreateInfo = &ci;
  VkMemoryRequirements2 out{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  vkGetDeviceImageMemoryRequirements(device.handle(), &q, &out);
  return out.memoryRequirements;
}

void Image::create(Device& device, const ImageInfo& info, std::string_view name) {
  device_ = &device;
  info_ = info;
  name_ = name;
  VkImageCreateInfo ci = imageCreateInfo(info);
  VkResult r = vkCreateImage(device.handle(), &ci, nullptr, &image_);
  if (r == VK_ERROR_FORMAT_NOT_SUPPORTED) throw Error(fmt::format("image `{}`: format not supported for its usage", name));
  TL_VK(r);
  device.setName(VK_OBJECT_TYPE_IMAGE, uint64_t(image_), name);
}

Image::Image(Device& device, const ImageInfo& info, std::string_view name) {
  create(device, info, name);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device.handle(), image_, &req);
  ownMemory_ = Memory(device, req, MemoryUsage::GpuOnly, name);
  TL_VK(vkBindImageMemory(device.handle(), image_, ownMemory_.handle(), 0));
  createViews();
}

Image::Image(Device& device, const ImageInfo& info, VkDeviceMemory memory, VkDeviceSize offset, std::string_view name) {
  create(device, info, name);
  TL_VK(vkBindImageMemory(device.handle(), image_, memory, offset));
  createViews();
}

VkImageAspectFlags Image::aspect() const {
  return isDepthFormat(info_.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

void Image::createViews() {
  auto makeView = [&](uint32_t base, uint32_t count, std::string_view suffix) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image_;
    vi.viewType = is3D() ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    vi.format = info_.format;
    vi.subresourceRange = {aspect(), base, count, 0, 1};
    VkImageView v;
    TL_VK(vkCreateImageView(device_->handle(), &vi, nullptr, &v));
    device_->setName(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(v), fmt::format("{}{}", name_, suffix));
    return v;
  };
  view_ = makeView(0, info_.mipLevels, "");
  if (info_.mipLevels > 1) {
    for (uint32_t m = 0; m < info_.mipLevels; ++m) mipViews_.push_back(makeView(m, 1, fmt::format(".mip{}", m)));
  } else {
    mipViews_.push_back(view_);
  }
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    mipViews_ = std::move(o.mipViews_);
    ownMemory_ = std::move(o.ownMemory_);
    info_ = o.info_;
    name_ = std::move(o.name_);
  }
  return *this;
}

void Image::reset() {
  if (image_) {
    VkDevice d = device_->handle();
    VkImage img = image_;
    std::vector<VkImageView> views;
    views.push_back(view_);
    for (auto v : mipViews_)
      if (v != view_) views.push_back(v);
    device_->destroyLater([d, img, views] {
      for (auto v : views) vkDestroyImageView(d, v, nullptr);
      vkDestroyImage(d, img, nullptr);
    });
  }
  image_ = VK_NULL_HANDLE;
  view_ = VK_NULL_HANDLE;
  mipViews_.clear();
  ownMemory_.reset();
}

// ---- Sampler ---------------------------------------------------------------------------

Sampler::Sampler(Device& device, VkFilter filter, VkSamplerAddressMode address, std::string_view name,
                 bool compareDepth, float maxAnisotropy)
    : device_(&device) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = filter;
  ci.mipmapMode = filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = address;
  ci.maxLod = VK_LOD_CLAMP_NONE;
  ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  ci.compareEnable = compareDepth;
  ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  if (maxAnisotropy > 1.0f) {
    ci.anisotropyEnable = VK_TRUE;
    ci.maxAnisotropy = std::min(maxAnisotropy, device.limits().maxSamplerAnisotropy);
  }
  TL_VK(vkCreateSampler(device.handle(), &ci, nullptr, &sampler_));
  device.setName(VK_OBJECT_TYPE_SAMPLER, uint64_t(sampler_), name);
}

Sampler::Sampler(Device& device, const VkSamplerCreateInfo& info, std::string_view name) : device_(&device) {
  TL_VK(vkCreateSampler(device.handle(), &info, nullptr, &sampler_));
  device.setName(VK_OBJECT_TYPE_SAMPLER, uint64_t(sampler_), name);
}

Sampler& Sampler::operator=(Sampler&& o) noexcept {
  if (this != &o) {
    reset();
    device_ = std::exchange(o.device_, nullptr);
    sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

void Sampler::reset() {
  if (sampler_) {
    VkDevice d = device_->handle();
    VkSampler s = sampler_;
    device_->destroyLater([d, s] { vkDestroySampler(d, s, nullptr); });
  }
  sampler_ = VK_NULL_HANDLE;
}

// ---- transfers -------------------------------------------------------------------------

void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                     uint32_t baseMip, uint32_t mipCount) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, baseMip, mipCount, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to) {
  transitionImage(cmd, image.handle(), image.aspect(), from, to);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void copyImage(VkCommandBuffer cmd, const Image& src, const Image& dst) {
  VkImageCopy region{};
  region.srcSubresource = region.dstSubresource = {src.aspect(), 0, 0, 1};
  region.extent = src.extent();
  vkCmdCopyImage(cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 1, &region);
}

void blitImage(VkCommandBuffer cmd, const Image& src, const Image& dst) {
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(src.extent().width), int32_t(src.extent().height), int32_t(src.extent().depth)};
  blit.dstOffsets[1] = {int32_t(dst.extent().width), int32_t(dst.extent().height), int32_t(dst.extent().depth)};
  vkCmdBlitImage(cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                 &blit, VK_FILTER_NEAREST);
}

void clearImage(VkCommandBuffer cmd, const Image& image, VkImageLayout layout) {
  VkClearColorValue zero{};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, image.handle(), layout, &zero, 1, &range);
}

void uploadBuffer(Device& device, Buffer& dst, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  Buffer staging(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging.upload");
  staging.write(data, bytes);
  device.immediate([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
  });
}

void uploadImage2D(Device& device, Image& dst, const void* texels, VkDeviceSize bytes) {
  Buffer staging(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging.upload");
  staging.write(texels, bytes);
  device.immediate([&](VkCommandBuffer cmd) {
    transitionImage(cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {dst.aspect(), 0, 0, 1};
    region.imageExtent = dst.extent();
    vkCmdCopyBufferToImage(cmd, staging.handle(), dst.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transitionImage(cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
}

}  // namespace tl::gpu

#include "gpu/formats.h"

namespace tl::gpu {

std::vector<uint8_t> readbackImage(Device& device, const Image& image, VkImageLayout layout) {
  FormatInfo fi = formatInfo(image.format());
  TL_CHECK(fi.bytes > 0, "image `{}`: read-back of this format is not supported", image.name());
  VkExtent3D e = image.extent();
  VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * e.depth * fi.bytes;
  Buffer staging(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "staging.readback");
  device.immediate([&](VkCommandBuffer cmd) {
    transitionImage(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect(), 0, 0, 1};
    region.imageExtent = e;
    vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
  });
  std::vector<uint8_t> out(bytes);
  std::memcpy(out.data(), staging.mapped(), bytes);
  return out;
}

}  // namespace tl::gpu

namespace tl::gpu {

void uploadImage2DWithMips(Device& device, Image& dst, const void* texels, VkDeviceSize bytes) {
  Buffer staging(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging.upload");
  staging.write(texels, bytes);
  const uint32_t mips = dst.info().mipLevels;
  auto barrier = [&](VkCommandBuffer cmd, uint32_t mip, VkImageLayout from, VkImageLayout to) {
    transitionImage(cmd, dst.handle(), VK_IMAGE_ASPECT_COLOR_BIT, from, to, mip, 1);
  };
  device.immediate([&](VkCommandBuffer cmd) {
    transitionImage(cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = dst.extent();
    vkCmdCopyBufferToImage(cmd, staging.handle(), dst.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    int32_t w = int32_t(dst.extent().width), h = int32_t(dst.extent().height);
    for (uint32_t m = 1; m < mips; ++m) {
      barrier(cmd, m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
      blit.srcOffsets[1] = {w, h, 1};
      w = std::max(1, w / 2), h = std::max(1, h / 2);
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
      blit.dstOffsets[1] = {w, h, 1};
      vkCmdBlitImage(cmd, dst.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(),
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
      barrier(cmd, m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
    barrier(cmd, mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
}

}  // namespace tl::gpu
