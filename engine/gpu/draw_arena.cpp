#include "gpu/draw_arena.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>

namespace tl::gpu {
namespace {

// A slot's memory comes in chunks of at least this much (12,000 indexed draws); a larger list
// gets a chunk of its own size, rounded up to a power of two.
constexpr VkDeviceSize kChunkBytes = 256 * 1024;

}  // namespace

DrawArena::Placed DrawArena::place(uint64_t frame, const void* data, VkDeviceSize bytes) {
  Slot& slot = slots_[frame % kMaxFramesInFlight];
  if (slot.frame != frame) slot.frame = frame, slot.chunk = 0, slot.used = 0;
  // The list stays whole in one chunk (one call reads it): the next chunk that holds it.
  while (slot.chunk < slot.chunks.size() && slot.chunks[slot.chunk].size() - slot.used < bytes)
    ++slot.chunk, slot.used = 0;
  if (slot.chunk == slot.chunks.size()) {
    const VkDeviceSize size = std::max(kChunkBytes, std::bit_ceil(bytes));
    slot.chunks.emplace_back(*device_, size, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, MemoryUsage::Upload,
                             fmt::format("draws[{}].{}", frame % kMaxFramesInFlight, slot.chunks.size()));
  }
  Buffer& chunk = slot.chunks[slot.chunk];
  const Placed placed{chunk.handle(), slot.used};
  chunk.write(data, bytes, slot.used);
  slot.used += bytes;
  return placed;
}

uint32_t DrawArena::drawsPerCall() const { return std::max(device_->limits().maxDrawIndirectCount, 1u); }

// One list, either kind of draw: `direct` records one draw (a device without multi-draw),
// `indirect` one call over `count` of the list's commands placed at `offset`.
template <class Command, class Direct, class Indirect>
void DrawArena::record(uint64_t frame, const std::vector<Command>& draws, Direct direct, Indirect indirect) {
  if (draws.empty()) return;
  draws_ += draws.size();
  if (!device_->multiDrawIndirect()) {
    for (const Command& d : draws) direct(d), ++calls_;
    return;
  }
  constexpr uint32_t stride = sizeof(Command);
  const Placed at = place(frame, draws.data(), draws.size() * stride);
  for (size_t first = 0; first < draws.size(); first += drawsPerCall()) {
    const uint32_t count = uint32_t(std::min<size_t>(drawsPerCall(), draws.size() - first));
    indirect(at.buffer, at.offset + first * stride, count, stride);
    ++calls_;
  }
}

void DrawArena::drawIndexed(VkCommandBuffer cmd, uint64_t frame,
                            const std::vector<VkDrawIndexedIndirectCommand>& draws) {
  record(
      frame, draws,
      [cmd](const VkDrawIndexedIndirectCommand& d) {
        vkCmdDrawIndexed(cmd, d.indexCount, d.instanceCount, d.firstIndex, d.vertexOffset, d.firstInstance);
      },
      [cmd](VkBuffer buffer, VkDeviceSize offset, uint32_t count, uint32_t stride) {
        vkCmdDrawIndexedIndirect(cmd, buffer, offset, count, stride);
      });
}

void DrawArena::draw(VkCommandBuffer cmd, uint64_t frame, const std::vector<VkDrawIndirectCommand>& draws) {
  record(
      frame, draws,
      [cmd](const VkDrawIndirectCommand& d) {
        vkCmdDraw(cmd, d.vertexCount, d.instanceCount, d.firstVertex, d.firstInstance);
      },
      [cmd](VkBuffer buffer, VkDeviceSize offset, uint32_t count, uint32_t stride) {
        vkCmdDrawIndirect(cmd, buffer, offset, count, stride);
      });
}

}  // namespace tl::gpu
