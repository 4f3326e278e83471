// RenderDoc's in-application API, when the process runs under RenderDoc (launched from
// qrenderdoc or `renderdoccmd capture`): a capture of exactly one frame on request. Every
// pass and resource already carries its graph name as a debug label, so the capture reads
// like the frame graph. Outside RenderDoc it is unavailable, with the reason.
#pragma once

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <optional>
#include <string>

namespace tl::gpu {

class RenderDoc {
 public:
  // Looks once for an already loaded librenderdoc.so (it never loads one itself).
  static RenderDoc& get();
  bool attached() const { return api_ != nullptr; }
  const std::string& unavailableReason() const { return reason_; }

  // Brackets one frame's GPU work (headless: no swapchain to trigger on).
  void startFrame(VkInstance instance);
  bool endFrame(VkInstance instance);  // false when RenderDoc captured nothing
  // The editor: capture the next presented frame.
  void triggerCapture();
  // Where captures go: a path template, RenderDoc appends the frame number.
  void setCaptureTemplate(const std::string& pathTemplate);
  uint32_t captureCount() const;
  std::optional<std::string> capturePath(uint32_t index) const;

 private:
  RenderDoc();
  const void* api_ = nullptr;  // RENDERDOC_API_1_4_1*
  std::string reason_;
};

}  // namespace tl::gpu
