// The albedo baker: renders each mesh + material combination from 6 orthographic
// directions fitted to its bounds and averages the hit albedo it shows, weighted by
// coverage (Metro's pre-filtered per-instance albedo). Many combinations share one atlas
// and one submission; a reduction on the GPU sums each tile, so only 16 bytes per view
// come back. Runs in its own render graph (resources albedo.bake.*).
#pragma once

#include "albedo/albedo_database.h"
#include "albedo/albedo_key.h"
#include "graph/executor.h"
#include "scene/gpu_scene.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tl::albedo {

inline constexpr graph::ImageName kBakeAtlas{"albedo.bake.atlas"};
inline constexpr graph::ImageName kBakeDepth{"albedo.bake.depth"};
inline constexpr graph::BufferName kBakeSums{"albedo.bake.sums"};

struct BakeOutcome {
  AlbedoKey key = 0;
  std::optional<BakedEntry> entry;  // empty: nothing to store (why says why)
  std::string error;                // why there is no entry
  // No texel of it is seen from any of the views: an empty mesh or a fully cut-out material
  // (alpha below its cutoff everywhere). No ray can hit it, so there is no albedo to bake: it is
  // what it is, not a failure.
  bool invisible = false;
};

class AlbedoBaker {
 public:
  AlbedoBaker(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene, const BakeSettings& settings);

  // How many combinations one bake() call renders in one submission.
  static uint32_t maxBatch();
  // Each key has a fixed place in the atlas: the texels a combination rasterises to (and so
  // its baked value, to the last bit) never depend on what else is in its batch, so shards,
  // resumed bakes and whole bakes agree exactly. A batch holds at most one key per slot.
  static uint32_t bakeSlot(AlbedoKey key);
  // Bakes up to maxBatch() combinations in distinct slots (else throws). Outcomes in order.
  std::vector<BakeOutcome> bake(const std::vector<const Combination*>& batch);
  // The last batch's atlas, for tests and the inspector.
  const graph::Readback* lastAtlas() const;
  void keepAtlas(bool keep) { keepAtlas_ = keep; }

 private:
  gpu::Device& device_;
  const scene::Scene& scene_;
  scene::GpuScene& gpuScene_;
  BakeSettings settings_;
  graph::Executor executor_;
  bool keepAtlas_ = false;
};

// Turns 6 views' sums (rgb sum of hit albedo over covered pixels, w covered pixels) into
// the entry: pure, unit-tested. Empty when no view shows anything.
std::optional<BakedEntry> entryFromViewSums(AlbedoKey key, const std::array<glm::vec4, kViews>& sums, uint32_t tileSize);

// The orthographic view `view` (0..5: from +X, -X, +Y, -Y, +Z, -Z) of object-space bounds:
// square, centred, with a 2% margin; depth reversed (the nearest point maps to 1).
glm::mat4 bakeViewProjection(const scene::Bounds& bounds, int view);

}  // namespace tl::albedo
