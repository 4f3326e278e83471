// Which deforming meshes get their bottom level refitted this frame (Metro's throttle): a
// mesh whose vertices changed since its last refit gathers priority every frame, more when
// it is in the top level and large on screen; each frame the `top` highest and `random`
// others drawn from the rest (so nothing starves) are refitted, within a vertex budget. A
// mesh not chosen keeps tracing against its last refitted pose. Pure; tested without a GPU.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tl::lighting {

struct RefitCandidate {
  uint32_t mesh = 0;
  uint32_t vertices = 0;
  bool visible = false;     // in this frame's top level
  float screenSize = 0.0f;  // bounding-sphere radius / distance (the angle it covers)
};

struct RefitPolicy {
  uint32_t top = 16;                // highest priorities refitted each frame
  uint32_t random = 4;              // plus this many others, drawn at random
  uint64_t vertexBudget = 1u << 20; // vertices refitted per frame at most (the first pick always goes)
};

class RefitScheduler {
 public:
  // `stale`: the meshes whose vertices changed since their last refit. Returns the ones to
  // refit now (their priority starts over); the others keep what they gathered.
  std::vector<uint32_t> choose(const std::vector<RefitCandidate>& stale, const RefitPolicy& policy, uint64_t frame);
  float priority(uint32_t mesh) const;
  // What one frame adds to a stale mesh's priority.
  static float gain(const RefitCandidate& c) { return c.visible ? 1.0f + 16.0f * c.screenSize : 0.1f; }

 private:
  std::unordered_map<uint32_t, float> priority_;
};

}  // namespace tl::lighting
