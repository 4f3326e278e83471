// Many draws as one call: a list of draw arguments written by the host into this frame's
// memory and recorded as one vkCmdDraw(Indexed)Indirect, where a call per draw cost the
// driver (and the validation layers, several times more) once per instance: a scene of ten
// thousand instances drew them ten thousand times per raster pass.
//
// The arguments are host-written before the frame is submitted, like push constants: no pass
// writes them, so the render graph has nothing to order (a submission makes the host's
// writes visible to the device). Frame f writes into its own slot (f % kMaxFramesInFlight),
// whose last user, frame f - kMaxFramesInFlight, has finished before frame f is built (the
// executor refuses more frames in flight, as gpu/upload_ring.h relies on too). A slot's
// memory grows to the largest frame seen and is reused after: a steady frame allocates nothing.
//
// Where the device lacks multiDrawIndirect or drawIndirectFirstInstance (optional Vulkan
// features; every desktop GPU and lavapipe have them), the same list is drawn one call per
// draw, as before.
#pragma once

#include "gpu/resources.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tl::gpu {

class DrawArena {
 public:
  DrawArena() = default;
  explicit DrawArena(Device& device) : device_(&device) {}

  // Records `draws` for frame `frame` (the executor's frame number), in their order.
  void drawIndexed(VkCommandBuffer cmd, uint64_t frame, const std::vector<VkDrawIndexedIndirectCommand>& draws);
  void draw(VkCommandBuffer cmd, uint64_t frame, const std::vector<VkDrawIndirectCommand>& draws);

  // Draw calls recorded since creation, and how many draws they held: counts for tests and
  // figures (a multi-draw call holds many).
  uint64_t calls() const { return calls_; }
  uint64_t draws() const { return draws_; }

 private:
  struct Placed {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
  };
  template <class Command, class Direct, class Indirect>
  void record(uint64_t frame, const std::vector<Command>& draws, Direct direct, Indirect indirect);
  // Copies `bytes` into frame `frame`'s slot: where it was put.
  Placed place(uint64_t frame, const void* data, VkDeviceSize bytes);
  // At most the device's maxDrawIndirectCount draws per call.
  uint32_t drawsPerCall() const;

  struct Slot {
    uint64_t frame = UINT64_MAX;  // the frame its contents belong to
    std::vector<Buffer> chunks;
    size_t chunk = 0;       // the one being filled
    VkDeviceSize used = 0;  // bytes of it
  };
  Device* device_ = nullptr;
  std::array<Slot, kMaxFramesInFlight> slots_;
  uint64_t calls_ = 0, draws_ = 0;
};

}  // namespace tl::gpu
