#include "gpu/upload_ring.h"

#include "gpu/check.h"

#include <fmt/format.h>

#include <cstring>

namespace tl::gpu {

UploadRing::UploadRing(Device& device, VkDeviceSize bytes, VkBufferUsageFlags usage, std::string_view name)
    : latest_(size_t(bytes), uint8_t(0)) {
  for (uint32_t i = 0; i < kMaxFramesInFlight; ++i)
    copies_[i] = Buffer(device, bytes, usage, MemoryUsage::Upload, fmt::format("{}[{}]", name, i));
}

void UploadRing::write(uint64_t frame, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  TL_CHECK(offset <= latest_.size() && bytes <= latest_.size() - offset,
           "a write of {} bytes at {} does not fit the {}-byte upload ring", bytes, offset, latest_.size());
  if (bytes == 0) return;
  std::memcpy(latest_.data() + offset, data, size_t(bytes));
  const size_t slot = size_t(frame % kMaxFramesInFlight);
  // A copy that held the bytes before this write needs only the written range.
  if (version_[slot] == latestVersion_)
    copies_[slot].write(data, bytes, offset);
  else
    copies_[slot].write(latest_.data(), latest_.size());
  version_[slot] = ++latestVersion_;
}

Buffer& UploadRing::forFrame(uint64_t frame) {
  TL_CHECK(!latest_.empty(), "an empty upload ring has no buffer to bind");
  const size_t slot = size_t(frame % kMaxFramesInFlight);
  if (version_[slot] != latestVersion_) {
    copies_[slot].write(latest_.data(), latest_.size());
    version_[slot] = latestVersion_;
  }
  return copies_[slot];
}

}  // namespace tl::gpu
