// A bake of one scene into one database, a batch at a time: the command line loops over
// step(), the editor calls it once per frame so the UI stays alive and can cancel. Keys the
// database already holds are skipped, so a bake that was killed resumes where it stopped;
// each batch is written in one transaction.
#pragma once

#include "albedo/albedo_baker.h"

#include <atomic>
#include <functional>

namespace tl::albedo {

struct BakeOptions {
  BakeSettings settings;
  uint32_t shardIndex = 0, shardCount = 1;  // bake only keys with key % count == index
  uint32_t batchSize = 0;                   // combinations per submission; 0 = as many as fit
  bool force = false;                       // re-bake keys the database already holds
  // Crash tests only: called inside a batch's transaction after its rows are written and
  // before the commit.
  std::function<void(uint32_t batch)> beforeCommit;
};

struct BakeProgress {
  uint32_t total = 0;      // keys in this shard
  uint32_t done = 0;       // baked + skipped + invisible + failed so far
  uint32_t baked = 0, skipped = 0, failed = 0;
  // Keys nothing of which is visible from any direction (an empty mesh, a material cut out
  // everywhere): no ray hits them, so nothing is stored for them. Not failures: a scene with a
  // fully cut-out mesh bakes to completion.
  uint32_t invisible = 0;
  std::vector<std::string> invisibleKeys;  // "key label"
  std::vector<std::string> failures;  // "key label: why"
  double gpuSeconds = 0.0;            // wall time spent in bake() calls
  bool cancelled = false;
};

class BakeJob {
 public:
  BakeJob(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene, AlbedoDatabase& db,
          BakeOptions options);

  // Bakes the next batch and commits it. False when nothing is left (or cancelled).
  bool step();
  void cancel() { cancelled_ = true; }
  const BakeProgress& progress() const { return progress_; }
  bool finished() const { return next_ >= todo_.size() || cancelled_; }

 private:
  AlbedoDatabase& db_;
  BakeOptions options_;
  SceneKeys keys_;
  AlbedoBaker baker_;
  std::vector<const Combination*> todo_;
  size_t next_ = 0;
  uint32_t batchIndex_ = 0;
  BakeProgress progress_;
  std::atomic<bool> cancelled_{false};
};

}  // namespace tl::albedo
