// A host-written buffer that frames in flight share. While the host writes frame f's
// contents the GPU may still read what frame f-1 wrote, so the ring keeps one copy per frame
// in flight and frame f uses copy f % kMaxFramesInFlight: the copy it overwrites was last
// used by frame f - kMaxFramesInFlight, which has finished before frame f is built (the
// executor refuses more frames in flight). Contents written once and then kept (a table
// changed only by edits) stay right in every copy: the ring keeps the host's latest bytes and
// brings a copy up to date when a frame takes it.
#pragma once

#include "gpu/resources.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tl::gpu {

class UploadRing {
 public:
  UploadRing() = default;
  UploadRing(Device& device, VkDeviceSize bytes, VkBufferUsageFlags usage, std::string_view name);

  // The bytes frame `frame` and the frames after it see: written into frame's copy now, into
  // the other copies when their frames take them.
  void write(uint64_t frame, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  // Frame `frame`'s copy, holding the latest bytes (what a frame binds).
  Buffer& forFrame(uint64_t frame);

  VkDeviceSize size() const { return latest_.size(); }
  explicit operator bool() const { return !latest_.empty(); }

 private:
  std::array<Buffer, kMaxFramesInFlight> copies_;
  std::array<uint64_t, kMaxFramesInFlight> version_{};  // of the latest bytes each copy holds
  std::vector<uint8_t> latest_;
  uint64_t latestVersion_ = 0;
};

}  // namespace tl::gpu
