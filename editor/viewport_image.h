// The engine's latest finished frame on the window's device. The engine renders on a device
// of its own (lavapipe, like many drivers, has one queue: a window sharing it would present
// only after every engine frame, at the engine's pace), reads its display image back, and
// the window's thread uploads those pixels here and blits them under the panels.
#pragma once

#include "gpu/resources.h"
#include "graph/executor.h"

#include <optional>

namespace tl::editor {

class ViewportImage {
 public:
  explicit ViewportImage(gpu::Device& device) : device_(device) {}

  // Pixels of a finished frame (display.ldr, rgba8): uploaded by the next record().
  void set(const graph::Readback& display);
  bool empty() const { return !image_ && !staged_; }
  void clear();
  // Records the upload of new pixels (if any) and the blit of the image, scaled, into
  // `target` (TRANSFER_DST_OPTIMAL) over the rectangle [min, max) in window pixels.
  void record(VkCommandBuffer cmd, VkImage target, VkExtent2D targetExtent, glm::ivec2 min, glm::ivec2 max);

 private:
  gpu::Device& device_;
  gpu::Image image_;  // left in TRANSFER_SRC_OPTIMAL between frames
  std::optional<gpu::Buffer> staged_;
  VkExtent2D stagedExtent_{};
};

}  // namespace tl::editor
