#include "viewport_image.h"

#include "gpu/formats.h"

#include <algorithm>

namespace tl::editor {

void ViewportImage::set(const graph::Readback& display) {
  if (display.extent.width == 0 || display.extent.height == 0 || display.format != VK_FORMAT_R8G8B8A8_UNORM) return;
  const VkDeviceSize bytes = VkDeviceSize(display.extent.width) * display.extent.height * 4;
  if (display.bytes.size() < bytes) return;
  // A fresh staging buffer each time: the one before may still be read by a UI frame in
  // flight (its destruction waits for that frame).
  staged_.emplace(device_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUsage::Upload, "ui.viewport.staging");
  staged_->write(display.bytes.data(), bytes);
  stagedExtent_ = {display.extent.width, display.extent.height};
}

void ViewportImage::clear() {
  staged_.reset();
  image_ = gpu::Image();
}

void ViewportImage::record(VkCommandBuffer cmd, VkImage target, VkExtent2D targetExtent, glm::ivec2 min, glm::ivec2 max) {
  if (staged_) {
    if (!image_ || image_.extent().width != stagedExtent_.width || image_.extent().height != stagedExtent_.height)
      image_ = gpu::Image(device_,
                          {VK_FORMAT_R8G8B8A8_UNORM, {stagedExtent_.width, stagedExtent_.height, 1}, 1,
                           VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT},
                          "ui.viewport");
    gpu::transitionImage(cmd, image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {stagedExtent_.width, stagedExtent_.height, 1};
    vkCmdCopyBufferToImage(cmd, staged_->handle(), image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    gpu::transitionImage(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    staged_.reset();
  }
  if (!image_) return;
  const int32_t x0 = std::clamp(min.x, 0, int32_t(targetExtent.width)), y0 = std::clamp(min.y, 0, int32_t(targetExtent.height));
  const int32_t x1 = std::clamp(max.x, 0, int32_t(targetExtent.width)), y1 = std::clamp(max.y, 0, int32_t(targetExtent.height));
  if (x1 <= x0 || y1 <= y0) return;
  // The blit writes over the target's clear: it waits for it.
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(image_.extent().width), int32_t(image_.extent().height), 1};
  blit.dstOffsets[0] = {x0, y0, 0};
  blit.dstOffsets[1] = {x1, y1, 1};
  vkCmdBlitImage(cmd, image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                 &blit, VK_FILTER_LINEAR);
}

}  // namespace tl::editor
