#include "window_presenter.h"

#include "session/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <imgui_impl_vulkan.h>

namespace tl::editor {

DrawDataCopy::DrawDataCopy(const ImDrawData& data)
    : displayPos_(data.DisplayPos), displaySize_(data.DisplaySize), framebufferScale_(data.FramebufferScale), valid_(data.Valid) {
  lists_.reserve(size_t(data.CmdListsCount));
  for (int l = 0; l < data.CmdListsCount; ++l) {
    const ImDrawList& src = *data.CmdLists[l];
    List list;
    list.vertices.assign(src.VtxBuffer.begin(), src.VtxBuffer.end());
    list.indices.assign(src.IdxBuffer.begin(), src.IdxBuffer.end());
    list.commands.assign(src.CmdBuffer.begin(), src.CmdBuffer.end());
    lists_.push_back(std::move(list));
  }
}

DrawDataCopy& DrawDataCopy::operator=(DrawDataCopy&& other) noexcept {
  if (this == &other) return *this;
  releaseViews();
  lists_ = std::move(other.lists_);
  displayPos_ = other.displayPos_, displaySize_ = other.displaySize_, framebufferScale_ = other.framebufferScale_;
  valid_ = other.valid_;
  views_ = std::move(other.views_);
  viewPointers_ = std::move(other.viewPointers_);
  data_ = other.data_;
  data_.CmdLists = viewPointers_.empty() ? nullptr : viewPointers_.data();
  return *this;
}

namespace {

// An ImVector that points at a std::vector's elements without owning them.
template <typename T>
void borrow(ImVector<T>& view, std::vector<T>& from) {
  view.Data = from.data();
  view.Size = view.Capacity = int(from.size());
}

template <typename T>
void unborrow(ImVector<T>& view) {
  view.Data = nullptr;
  view.Size = view.Capacity = 0;
}

}  // namespace

ImDrawData* DrawDataCopy::data() {
  releaseViews();
  data_ = ImDrawData{};
  data_.Valid = valid_;
  data_.DisplayPos = displayPos_, data_.DisplaySize = displaySize_, data_.FramebufferScale = framebufferScale_;
  for (List& list : lists_) {
    auto view = std::make_unique<ImDrawList>(nullptr);
    borrow(view->VtxBuffer, list.vertices);
    borrow(view->IdxBuffer, list.indices);
    borrow(view->CmdBuffer, list.commands);
    data_.TotalVtxCount += int(list.vertices.size());
    data_.TotalIdxCount += int(list.indices.size());
    viewPointers_.push_back(view.get());
    views_.push_back(std::move(view));
  }
  data_.CmdListsCount = int(viewPointers_.size());
  data_.CmdLists = viewPointers_.empty() ? nullptr : viewPointers_.data();
  return &data_;
}

void DrawDataCopy::releaseViews() {
  // The vectors are this object's: the ImDrawList must not free them.
  for (auto& view : views_) unborrow(view->VtxBuffer), unborrow(view->IdxBuffer), unborrow(view->CmdBuffer);
  views_.clear();
  viewPointers_.clear();
  data_.CmdLists = nullptr;
  data_.CmdListsCount = 0;
}

WindowPresenter::WindowPresenter(gpu::Device& device, VkSurfaceKHR surface, VkExtent2D size, bool vsync)
    : device_(device),
      swapchain_(std::make_unique<gpu::Swapchain>(device, surface, size, vsync)),
      viewportImage_(std::make_unique<ViewportImage>(device)) {}

WindowPresenter::~WindowPresenter() {
  stop();
  device_.waitIdle();
  viewportImage_.reset();
  swapchain_.reset();
}

void WindowPresenter::start() {
  if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
}

void WindowPresenter::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void WindowPresenter::submit(Frame frame) {
  {
    std::lock_guard lock(mutex_);
    if (waiting_) {
      ++superseded_;
      // What the replaced frame brought that the new one lacks still has to reach the window.
      if (!frame.image && !frame.clearImage && waiting_->image) frame.image = std::move(waiting_->image);
      if (!frame.image && waiting_->clearImage) frame.clearImage = true;
      if (!frame.screenshot) frame.screenshot = std::move(waiting_->screenshot);
    }
    waiting_ = std::move(frame);
  }
  wake_.notify_all();
}

void WindowPresenter::finish() {
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return (!waiting_ && !drawing_) || !thread_.joinable(); });
}

bool WindowPresenter::screenshotPending() const {
  std::lock_guard lock(mutex_);
  return (waiting_ && waiting_->screenshot) || screenshotInFlight_;
}

std::vector<std::string> WindowPresenter::takeErrors() {
  std::lock_guard lock(mutex_);
  return std::exchange(errors_, {});
}

void WindowPresenter::run() {
  for (;;) {
    Frame frame;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || waiting_; });
      if (!waiting_) break;  // stopping, nothing left to draw
      frame = std::move(*waiting_);
      waiting_.reset();
      drawing_ = true;
      screenshotInFlight_ = frame.screenshot.has_value();
    }
    std::string error;
    try {
      draw(frame);
    } catch (const std::exception& e) {
      error = fmt::format("the window could not be drawn: {}", e.what());
    }
    {
      std::lock_guard lock(mutex_);
      if (!error.empty()) errors_.push_back(error);
      drawing_ = false;
      screenshotInFlight_ = false;
    }
    done_.notify_all();
  }
  done_.notify_all();
}

void WindowPresenter::draw(Frame& frame) {
  if (frame.clearImage) viewportImage_->clear();
  if (frame.image) viewportImage_->set(*frame.image);
  // A resize, a vsync change, or a swapchain the window outgrew: made again, then drawn.
  for (int attempt = 0; attempt < 2; ++attempt) {
    const VkExtent2D have = swapchain_->extent();
    if (outOfDate_ || have.width != frame.windowSize.width || have.height != frame.windowSize.height ||
        swapchain_->vsync() != frame.vsync) {
      swapchain_->recreate(frame.windowSize, frame.vsync);
      outOfDate_ = false;
    }
    if (recordAndPresent(frame)) return;
    outOfDate_ = true;
  }
}

bool WindowPresenter::recordAndPresent(Frame& frame) {
  auto& d = device_;
  if (!swapchain_->acquire()) return false;
  VkCommandBuffer cmd = d.beginCommands();
  VkImage target = swapchain_->image();
  VkExtent2D ext = swapchain_->extent();
  gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkClearColorValue clear{{0.09f, 0.09f, 0.10f, 1.0f}};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
  // The engine's latest image, scaled into the viewport panel (linear filter: render scale).
  if (frame.viewportMax.x > frame.viewportMin.x && frame.viewportMax.y > frame.viewportMin.y)
    viewportImage_->record(cmd, target, ext, frame.viewportMin, frame.viewportMax);

  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = swapchain_->renderPass();
  rp.framebuffer = swapchain_->framebuffer();
  rp.renderArea = {{0, 0}, ext};
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(frame.ui.data(), cmd);
  vkCmdEndRenderPass(cmd);

  std::optional<gpu::Buffer> shot;
  if (frame.screenshot) {
    shot.emplace(d, VkDeviceSize(ext.width) * ext.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                 "ui.screenshot");
    gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {ext.width, ext.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shot->handle(), 1, &region);
    gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  }
  const bool presented = swapchain_->submitAndPresent(cmd);
  if (presented) ++presented_;
  if (shot) {
    d.wait(swapchain_->lastSubmission());
    writeScreenshot(*shot, ext, *frame.screenshot);
  }
  return presented;
}

void WindowPresenter::writeScreenshot(const gpu::Buffer& pixels, VkExtent2D ext, const std::filesystem::path& file) {
  std::vector<uint8_t> rgb(size_t(ext.width) * ext.height * 3);
  const auto* src = static_cast<const uint8_t*>(pixels.mapped());
  const bool bgra = swapchain_->format() == VK_FORMAT_B8G8R8A8_UNORM;
  for (size_t i = 0; i < size_t(ext.width) * ext.height; ++i) {
    rgb[i * 3 + 0] = src[i * 4 + (bgra ? 2 : 0)];
    rgb[i * 3 + 1] = src[i * 4 + 1];
    rgb[i * 3 + 2] = src[i * 4 + (bgra ? 0 : 2)];
  }
  try {
    session::writeFileAtomically(file, [&](const std::string& tmp) {
      auto out = OIIO::ImageOutput::create(file.string());
      OIIO::ImageSpec spec(int(ext.width), int(ext.height), 3, OIIO::TypeDesc::UINT8);
      return out && out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) && out->close();
    });
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    errors_.push_back(fmt::format("cannot write the screenshot: {}", e.what()));
    return;
  }
  fmt::print("wrote {}\n", std::filesystem::absolute(file).string());
}

}  // namespace tl::editor
