#include "albedo/bake_job.h"

#include <chrono>

namespace tl::albedo {

BakeJob::BakeJob(gpu::Device& device, const scene::Scene& scene, scene::GpuScene& gpuScene, AlbedoDatabase& db,
                 BakeOptions options)
    : db_(db), options_(std::move(options)), keys_(sceneKeys(scene, options_.settings)),
      baker_(device, scene, gpuScene, options_.settings) {
  for (const Combination& c : keys_.combinations) {
    if (!inShard(c.key, options_.shardIndex, options_.shardCount)) continue;
    ++progress_.total;
    if (!options_.force && db_.hasBaked(c.key)) {
      ++progress_.skipped;
      ++progress_.done;
    } else {
      todo_.push_back(&c);
    }
  }
}

bool BakeJob::step() {
  if (cancelled_) progress_.cancelled = true;
  if (finished()) return false;
  // The next keys in order whose atlas slots are free; the rest wait for a later batch.
  const size_t limit = options_.batchSize ? std::min(options_.batchSize, AlbedoBaker::maxBatch()) : AlbedoBaker::maxBatch();
  std::vector<bool> slotUsed(AlbedoBaker::maxBatch(), false);
  std::vector<const Combination*> batch, later;
  for (size_t i = next_; i < todo_.size(); ++i) {
    const uint32_t slot = AlbedoBaker::bakeSlot(todo_[i]->key);
    if (batch.size() < limit && !slotUsed[slot]) {
      slotUsed[slot] = true;
      batch.push_back(todo_[i]);
    } else {
      later.push_back(todo_[i]);
    }
  }
  std::copy(batch.begin(), batch.end(), todo_.begin() + next_);
  std::copy(later.begin(), later.end(), todo_.begin() + next_ + batch.size());
  const size_t end = next_ + batch.size();

  const auto start = std::chrono::steady_clock::now();
  std::vector<BakeOutcome> outcomes = baker_.bake(batch);
  progress_.gpuSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<BakedEntry> rows;
  const std::string now = utcNow();
  for (size_t i = 0; i < outcomes.size(); ++i) {
    if (outcomes[i].entry) {
      rows.push_back(*outcomes[i].entry);
      rows.back().bakedAt = now;
    } else if (outcomes[i].invisible) {
      ++progress_.invisible;
      progress_.invisibleKeys.push_back(keyToHex(outcomes[i].key) + " " + batch[i]->label);
    } else {
      ++progress_.failed;
      progress_.failures.push_back(keyToHex(outcomes[i].key) + " " + batch[i]->label + ": " + outcomes[i].error);
    }
  }
  const uint32_t index = batchIndex_++;
  db_.writeBaked(rows, options_.beforeCommit ? std::function<void()>([&] { options_.beforeCommit(index); })
                                             : std::function<void()>());
  progress_.baked += uint32_t(rows.size());
  progress_.done += uint32_t(batch.size());
  next_ = end;
  return !finished();
}

}  // namespace tl::albedo
