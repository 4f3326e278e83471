#include "gpu/swapchain.h"

#include <fmt/format.h>

#include <algorithm>

namespace tl::gpu {

Swapchain::Swapchain(Device& device, VkSurfaceKHR surface, VkExtent2D size, bool vsync)
    : device_(device), surface_(surface), vsync_(vsync) {
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(device.physical(), device.queueFamily(), surface, &supported);
  if (!supported) throw Error(fmt::format("{} cannot present to this window", device.name()));
  create(size);
}

Swapchain::~Swapchain() {
  device_.waitIdle();
  destroy();
  for (auto s : acquired_) vkDestroySemaphore(device_.handle(), s, nullptr);
  for (auto s : rendered_) vkDestroySemaphore(device_.handle(), s, nullptr);
  if (renderPass_) vkDestroyRenderPass(device_.handle(), renderPass_, nullptr);
}

void Swapchain::create(VkExtent2D size) {
  VkPhysicalDevice pd = device_.physical();
  VkSurfaceCapabilitiesKHR caps;
  TL_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps));
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, formats.data());
  // UNORM: the engine's display image is already sRGB-encoded and ImGui's colours are
  // authored for a UNORM target; an _SRGB swapchain would encode both twice.
  VkSurfaceFormatKHR chosen = formats.at(0);
  for (auto& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
      chosen = f;
  format_ = chosen.format;

  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, modes.data());
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always available: vsync
  if (!vsync_) {
    for (auto want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
      if (std::find(modes.begin(), modes.end(), want) != modes.end()) {
        mode = want;
        break;
      }
  }

  extent_ = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : size;
  extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
  extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  uint32_t count = std::max(caps.minImageCount + 1, 2u);
  if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = count;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  // Transfer: the viewport is blitted in, and screenshots are copied out.
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = mode;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = VK_NULL_HANDLE;
  TL_VK(vkCreateSwapchainKHR(device_.handle(), &ci, nullptr, &swapchain_));

  vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &n, images_.data());

  if (!renderPass_) {
    VkAttachmentDescription color{};
    color.format = format_;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &color;
    rp.subpassCount = 1;
    rp.pSubpasses = &sub;
    rp.dependencyCount = 1;
    rp.pDependencies = &dep;
    TL_VK(vkCreateRenderPass(device_.handle(), &rp, nullptr, &renderPass_));
    device_.setName(VK_OBJECT_TYPE_RENDER_PASS, uint64_t(renderPass_), "ui.renderPass");
  }
  for (size_t i = 0; i < images_.size(); ++i) {
    device_.setName(VK_OBJECT_TYPE_IMAGE, uint64_t(images_[i]), fmt::format("swapchain.{}", i));
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = images_[i];
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format_;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView v;
    TL_VK(vkCreateImageView(device_.handle(), &vi, nullptr, &v));
    views_.push_back(v);
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = renderPass_;
    fi.attachmentCount = 1;
    fi.pAttachments = &v;
    fi.width = extent_.width;
    fi.height = extent_.height;
    fi.layers = 1;
    VkFramebuffer fb;
    TL_VK(vkCreateFramebuffer(device_.handle(), &fi, nullptr, &fb));
    framebuffers_.push_back(fb);
  }
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  while (acquired_.size() < images_.size() + 1) {
    VkSemaphore s;
    TL_VK(vkCreateSemaphore(device_.handle(), &si, nullptr, &s));
    acquired_.push_back(s);
  }
  while (rendered_.size() < images_.size()) {
    VkSemaphore s;
    TL_VK(vkCreateSemaphore(device_.handle(), &si, nullptr, &s));
    rendered_.push_back(s);
  }
}

void Swapchain::destroy() {
  for (auto fb : framebuffers_) vkDestroyFramebuffer(device_.handle(), fb, nullptr);
  for (auto v : views_) vkDestroyImageView(device_.handle(), v, nullptr);
  framebuffers_.clear();
  views_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(VkExtent2D size, bool vsync) {
  device_.waitIdle();
  vsync_ = vsync;
  destroy();
  // Semaphores may be left signalled by an abandoned acquire: start from fresh ones.
  for (auto s : acquired_) vkDestroySemaphore(device_.handle(), s, nullptr);
  acquired_.clear();
  create(size);
}

bool Swapchain::acquire() {
  slot_ = (slot_ + 1) % uint32_t(acquired_.size());
  VkResult r = vkAcquireNextImageKHR(device_.handle(), swapchain_, UINT64_MAX, acquired_[slot_], VK_NULL_HANDLE, &current_);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) TL_VK(r);
  return true;
}

bool Swapchain::submitAndPresent(VkCommandBuffer cmd) {
  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = acquired_[slot_];
  wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = rendered_[current_];
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  lastSubmission_ = device_.submit(cmd, {wait}, {signal});
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered_[current_];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &current_;
  VkResult r = vkQueuePresentKHR(device_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  TL_VK(r);
  return true;
}

}  // namespace tl::gpu
