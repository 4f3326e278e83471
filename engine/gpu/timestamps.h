// GPU timestamps: one query pool, two queries per named scope, results in milliseconds.
// The graph executor opens a scope per pass; pass code never touches this.
#pragma once

#include "gpu/device.h"

#include <string>
#include <vector>

namespace tl::gpu {

struct ScopeTime {
  std::string name;
  double milliseconds = 0.0;
};

class TimestampPool {
 public:
  TimestampPool(Device& device, uint32_t maxScopes);
  ~TimestampPool();
  TimestampPool(const TimestampPool&) = delete;
  TimestampPool& operator=(const TimestampPool&) = delete;

  bool supported() const { return supported_; }
  void reset(VkCommandBuffer cmd);  // at the start of a frame's command buffer
  void begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd);
  // After the frame's submission has completed: the scopes in recording order.
  std::vector<ScopeTime> read();

 private:
  Device& device_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t maxScopes_ = 0;
  std::vector<std::string> names_;
  bool supported_ = false;
  double periodNs_ = 1.0;
};

}  // namespace tl::gpu
