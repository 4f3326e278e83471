#include "gpu/timestamps.h"

namespace tl::gpu {

TimestampPool::TimestampPool(Device& device, uint32_t maxScopes) : device_(device), maxScopes_(maxScopes) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device.physical(), &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(device.physical(), &n, families.data());
  supported_ = families[device.queueFamily()].timestampValidBits > 0 && device.limits().timestampPeriod > 0;
  periodNs_ = device.limits().timestampPeriod;
  if (!supported_) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = maxScopes * 2;
  TL_VK(vkCreateQueryPool(device.handle(), &ci, nullptr, &pool_));
  device.setName(VK_OBJECT_TYPE_QUERY_POOL, uint64_t(pool_), "timestamps");
}

TimestampPool::~TimestampPool() {
  if (pool_) {
    VkDevice d = device_.handle();
    VkQueryPool p = pool_;
    device_.destroyLater([d, p] { vkDestroyQueryPool(d, p, nullptr); });
  }
}

void TimestampPool::reset(VkCommandBuffer cmd) {
  names_.clear();
  if (supported_) vkCmdResetQueryPool(cmd, pool_, 0, maxScopes_ * 2);
}

void TimestampPool::begin(VkCommandBuffer cmd, const std::string& name) {
  if (!supported_ || names_.size() >= maxScopes_) return;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool_, uint32_t(names_.size() * 2));
  names_.push_back(name);
}

void TimestampPool::end(VkCommandBuffer cmd) {
  if (!supported_ || names_.empty() || names_.size() > maxScopes_) return;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_, uint32_t(names_.size() * 2 - 1));
}

std::vector<ScopeTime> TimestampPool::read() {
  std::vector<ScopeTime> out;
  if (!supported_ || names_.empty()) return out;
  std::vector<uint64_t> ticks(names_.size() * 2);
  VkResult r = vkGetQueryPoolResults(device_.handle(), pool_, 0, uint32_t(ticks.size()), ticks.size() * 8, ticks.data(), 8,
                                     VK_QUERY_RESULT_64_BIT);
  if (r != VK_SUCCESS) return out;
  for (size_t i = 0; i < names_.size(); ++i)
    out.push_back({names_[i], double(ticks[2 * i + 1] - ticks[2 * i]) * periodNs_ * 1e-6});
  return out;
}

}  // namespace tl::gpu
