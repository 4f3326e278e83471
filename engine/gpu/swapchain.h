// The window's swapchain: images, a render pass that loads them (the UI draws over the
// viewport image blitted in first), per-image framebuffers, acquire/present with the
// semaphores they need, resize and vsync. The surface comes from the editor (GLFW);
// nothing here knows about windows.
#pragma once

#include "gpu/resources.h"

#include <vector>

namespace tl::gpu {

class Swapchain {
 public:
  Swapchain(Device& device, VkSurfaceKHR surface, VkExtent2D size, bool vsync);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Recreates for a new window size or vsync setting (waits for the device).
  void recreate(VkExtent2D size, bool vsync);

  // False when the swapchain is out of date (resize it and skip the frame).
  bool acquire();
  // Submits `cmd` (waiting on the acquired image) and presents; false when out of date.
  bool submitAndPresent(VkCommandBuffer cmd);

  VkImage image() const { return images_[current_]; }
  VkFramebuffer framebuffer() const { return framebuffers_[current_]; }
  VkRenderPass renderPass() const { return renderPass_; }
  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  bool vsync() const { return vsync_; }
  // Last submission that used the swapchain: wait for it before reading an image back.
  uint64_t lastSubmission() const { return lastSubmission_; }

 private:
  void create(VkExtent2D size);
  void destroy();

  Device& device_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_B8G8R8A8_UNORM;
  VkExtent2D extent_{};
  bool vsync_ = true;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> acquired_;   // per acquire slot
  std::vector<VkSemaphore> rendered_;   // per swapchain image
  uint32_t slot_ = 0;
  uint32_t current_ = 0;
  uint64_t lastSubmission_ = 0;
};

}  // namespace tl::gpu
