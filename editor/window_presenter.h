// Draws and presents the editor's window on a thread of its own. On lavapipe presenting
// waits until the frame is drawn (~20 ms of CPU for the 1600x900 window, several times that
// in wall time when the cores are shared), which held the interface's loop up on every
// redraw. The UI loop hands over what to draw (a copy of Dear ImGui's draw data, the
// viewport's place, a new engine image, a screenshot to take) and goes on at its own rate;
// this thread draws the latest it was given. A frame given while another is being drawn
// replaces the one still waiting (its new engine image and screenshot carry over): the
// window shows the newest state, never a queue of old ones.
//
// The window's device (swapchain, Dear ImGui's Vulkan backend, the viewport image) is used
// only from this thread once started.
#pragma once

#include "viewport_image.h"

#include "gpu/swapchain.h"
#include "graph/executor.h"

#include <imgui.h>

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace tl::editor {

// Dear ImGui's draw data copied out of the frame (the context reuses its lists the next
// frame). Its ImDrawLists borrow this object's own vectors, so they are made and dropped
// without Dear ImGui's allocator (which counts allocations in the context the UI thread is
// using).
class DrawDataCopy {
 public:
  DrawDataCopy() = default;
  explicit DrawDataCopy(const ImDrawData& data);
  DrawDataCopy(DrawDataCopy&&) = default;  // vectors keep their buffers: borrowed pointers stay valid
  DrawDataCopy& operator=(DrawDataCopy&& other) noexcept;
  DrawDataCopy(const DrawDataCopy&) = delete;
  DrawDataCopy& operator=(const DrawDataCopy&) = delete;
  ~DrawDataCopy() { releaseViews(); }
  // For ImGui_ImplVulkan_RenderDrawData; valid until the copy changes or goes.
  ImDrawData* data();

 private:
  void releaseViews();
  struct List {
    std::vector<ImDrawVert> vertices;
    std::vector<ImDrawIdx> indices;
    std::vector<ImDrawCmd> commands;
  };
  std::vector<List> lists_;
  ImVec2 displayPos_{}, displaySize_{}, framebufferScale_{1.0f, 1.0f};
  bool valid_ = false;
  std::vector<std::unique_ptr<ImDrawList>> views_;
  std::vector<ImDrawList*> viewPointers_;
  ImDrawData data_{};
};

class WindowPresenter {
 public:
  struct Frame {
    DrawDataCopy ui;
    glm::ivec2 viewportMin{0}, viewportMax{0};  // window pixels, [min, max)
    VkExtent2D windowSize{};                    // the framebuffer's size now
    bool vsync = true;
    std::optional<graph::Readback> image;       // a new engine image (display.ldr)
    bool clearImage = false;                    // nothing under the panels (no scene)
    std::optional<std::filesystem::path> screenshot;
  };

  WindowPresenter(gpu::Device& device, VkSurfaceKHR surface, VkExtent2D size, bool vsync);
  ~WindowPresenter();
  // Before start(): Dear ImGui's Vulkan backend is set up on the swapchain's render pass.
  const gpu::Swapchain& swapchain() const { return *swapchain_; }
  void start();
  // Stops the thread after the frames given are drawn (before Dear ImGui's backend goes).
  void stop();
  void submit(Frame frame);
  // Waits until every frame given so far is presented (a screenshot written).
  void finish();
  bool screenshotPending() const;
  uint64_t presented() const { return presented_.load(); }
  uint64_t superseded() const { return superseded_.load(); }  // frames replaced before drawn
  // Errors met drawing (a screenshot not written, a device error), for the interface to show.
  std::vector<std::string> takeErrors();

 private:
  void run();
  void draw(Frame& frame);
  bool recordAndPresent(Frame& frame);  // false: the swapchain was out of date
  void writeScreenshot(const gpu::Buffer& pixels, VkExtent2D extent, const std::filesystem::path& file);

  gpu::Device& device_;
  std::unique_ptr<gpu::Swapchain> swapchain_;
  std::unique_ptr<ViewportImage> viewportImage_;
  bool outOfDate_ = false;

  mutable std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::optional<Frame> waiting_;
  bool drawing_ = false, stopping_ = false, screenshotInFlight_ = false;
  std::vector<std::string> errors_;
  std::thread thread_;
  std::atomic<uint64_t> presented_{0}, superseded_{0};
};

}  // namespace tl::editor
