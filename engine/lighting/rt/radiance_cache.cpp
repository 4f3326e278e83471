// The RT path's radiance cache: plan, accumulate, resolve (radiance_cache.h, shared/rt_cache.h).
#include "lighting/rt/radiance_cache.h"

#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "lighting/common/render_settings.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tl::lighting {

using graph::Usage;

RtCacheOutcomes countCacheOutcomes(std::span<const uint8_t> bytes) {
  RtCacheOutcomes o;
  for (size_t i = 0; i + sizeof(shared::RtCacheOutcome) <= bytes.size(); i += sizeof(shared::RtCacheOutcome)) {
    shared::RtCacheOutcome v;
    std::memcpy(&v, bytes.data() + i, sizeof v);
    if (v.outcome == shared::kRtCacheOutcomeNone) continue;
    ++o.paths;
    if (v.outcome == shared::kRtCacheOutcomeSky) ++o.sky;
    if (v.outcome == shared::kRtCacheOutcomeOnScreen) ++o.onScreen;
    if (v.outcome == shared::kRtCacheOutcomeOffScreen) ++o.offScreen;
    if (v.outcome == shared::kRtCacheOutcomeEnded) ++o.ended;
    // The shader writes finite, non-negative luminances; a file or device could still hand
    // back anything, and one bad value must not decide.
    if (std::isfinite(v.gathered) && v.gathered > 0.0f) o.gathered += v.gathered;
    if (std::isfinite(v.added) && v.added > 0.0f) o.added += v.added;
  }
  return o;
}

bool RtCacheSwitch::update(const RtCacheOutcomes& measured, float minGain) {
  if (measured.paths == 0) return on_;  // nothing seen (all sky): keep the decision
  const double share = measured.cacheGain();
  if (!on_ && share >= minGain) on_ = true;
  if (on_ && share < 0.5 * minGain) on_ = false;
  return on_;
}

namespace {
float largest(const glm::vec4& v) { return std::max({v.x, v.y, v.z}); }
graph::ResourceDesc entriesDesc(uint32_t entries) {
  return graph::ResourceDesc::buffer(VkDeviceSize(entries) * sizeof(shared::RtCacheEntry),
                                     "radiance cache: per cell C (rgb), samples (w), key");
}
graph::ResourceDesc accumDesc(uint32_t entries) {
  return graph::ResourceDesc::buffer(VkDeviceSize(entries) * sizeof(shared::RtCacheAccum),
                                     "radiance cache: per cell key, last frame sampled, fixed-point sums by frame parity");
}
}  // namespace

graph::ResourceDesc RtRadianceCache::samplesDesc(const FrameInputs& in) const {
  return graph::ResourceDesc::buffer(VkDeviceSize(paths(in)) * bounces_ * sizeof(shared::RtCacheSample),
                                     "radiance cache: each update path vertex's sample (cell, incoming radiance)");
}
graph::ResourceDesc RtRadianceCache::outcomesDesc(const FrameInputs& in) const {
  return graph::ResourceDesc::buffer(VkDeviceSize(paths(in)) * sizeof(shared::RtCacheOutcome),
                                     "radiance cache: each update path's first ray (0 none, 1 sky, 2 on screen, 3 off screen), "
                                     "the light it gathers and the light the cache adds there");
}

void RtRadianceCache::plan(graph::RenderGraph& graph, FrameInputs& in, shared::RtPush& push, float maxEmitterRadiance) {
  const RenderSettings& s = in.settings;
  // A new scene starts the switch over (off, measuring): the outcomes still held and the
  // decision they led to are another scene's, and an image must not depend on what was
  // rendered before it.
  // So does a session that dropped its histories (a new render from frame 0, a camera put
  // back): the same frames must give the same image whatever was rendered before.
  const uint64_t scene = in.key.hash(FramePart::Scene);
  if (scene != switchScene_ || in.historyResets != switchResets_) {
    switch_ = RtCacheSwitch{};
    measured_ = {};
    outcomes_.clear();
    ownFrames_.clear();
    switchScene_ = scene;
    switchResets_ = in.historyResets;
    ownFrame_ = 0;
    frame_ = 0;  // its sums' parity and its samples' seeds: the same from the same start
  }
  // This path's frame K decides from its frame K-2's outcomes, whether one frame is in flight
  // (K-1's are then at hand too, and wait a frame) or two (K-2's have just been collected):
  // the same frames decide the same frame, so an image does not depend on the frames in
  // flight. Its own count, not the session's: a live compare renders paths in turn.
  if (const graph::Readback* r = in.lastReadback(kRtCacheOutcomes))
    if (auto own = ownFrames_.find(r->frame); own != ownFrames_.end())
      outcomes_.try_emplace(own->second, countCacheOutcomes(r->bytes));
  if (ownFrame_ >= kOutcomeLag) {
    const uint64_t deciding = ownFrame_ - kOutcomeLag;
    if (auto it = outcomes_.find(deciding); it != outcomes_.end()) {
      measured_ = it->second;
      switch_.update(measured_, s.rtCacheMinGain);
    }
    outcomes_.erase(outcomes_.begin(), outcomes_.upper_bound(deciding));
    std::erase_if(ownFrames_, [&](const auto& f) { return f.second <= deciding; });
  }
  ownFrames_[in.frame] = ownFrame_++;
  active_ = s.rtCacheMinGain <= 1.0f && (s.rtCacheMinGain <= 0.0f || switch_.on());
  const uint32_t entries = s.rtCacheEntries;
  restart_ = false;
  if (active_) {
    const bool stored = wasActive_ && in.historyValid(kRtCacheEntries, entriesDesc(entries)) &&
                        in.historyValid(kRtCacheAccum, accumDesc(entries));
    const HistoryPolicy policy{"rt.cache", kRtCacheRestarts, 0u};
    restart_ = history_.advance(policy, in.key, "rt", in.historyLog, {stored}).action != HistoryAction::Keep;
  } else {
    history_.forget();
  }
  wasActive_ = active_;
  age_ = active_ && !restart_ ? age_ + 1u : 0u;

  // One path per tile of tile_ x tile_ pixels: the largest tile that gives rtCachePaths, so
  // the cache's samples (and cost) do not fall with the image size. Off, the probe paths go on
  // measuring: a sixteenth as many, two rays each (the second measures what the cache would add).
  const double pixels = double(s.width) * double(s.height);
  tile_ = uint32_t(std::max(1.0, std::floor(std::sqrt(pixels / double(std::max(s.rtCachePaths, 1u))))));
  if (!active_) tile_ *= 4u;
  bounces_ = active_ ? std::clamp(s.rtCacheBounces, 1u, shared::kRtCacheMaxBounces) : 2u;
  push.cacheLookup = active_ && !restart_ ? 1u : 0u;
  push.cacheEntryMask = entries - 1u;
  push.cacheCellSize = s.rtCacheCellSize;  // resolved: automatic at the scene's extent / 1000
  push.cacheCellAngle = s.rtCacheCellAngle;
  push.cacheBounces = bounces_;
  push.cacheTile = tile_;

  push_ = {};
  push_.entryMask = entries - 1u;
  push_.frame = active_ ? ++frame_ : frame_;
  push_.sampleCount = paths(in) * bounces_;
  push_.restart = restart_ ? 1u : 0u;
  // The brightest light one sample can carry, with room for the emitters' 1/pdf: the sun's,
  // the sky's and the light table's light off a white surface, an emitter seen directly. (Without
  // the light table a room lit only by lamps had a bound of 1e-3 and its cache held nothing.)
  const float light = std::max(largest(in.constants.sunIrradiance) / shared::kPi + largest(in.constants.skyRadiance) +
                                   in.lightTableRadiance,
                               maxEmitterRadiance);
  // Generous: a sample above it is clipped (lost light), and the sum's resolution is the bound
  // over 2^22 with stochastic rounding (no bias, only a little noise).
  push_.bound = 1024.0f * std::max(light, 1e-6f);
  push_.maxSamples = float(s.rtCacheMaxSamples);
  push_.maxAge = shared::kRtCacheMaxAge;
  push_.historyDecay = 1.0f - 1.0f / shared::kRtCacheHistoryFrames;
  graph.requestReadback(kRtCacheOutcomes);
}

void RtRadianceCache::addPasses(graph::RenderGraph& graph, FrameInputs& in) {
  if (!active_) return;
  const uint32_t entries = push_.entryMask + 1u;
  graph.declarePersistent(kRtCacheEntries, entriesDesc(entries));
  graph.declareCache(kRtCacheAccum, accumDesc(entries));
  ComputePass(in.device, "rt.cache.accumulate", "rt/cache_accumulate.comp")
      .bufferIn(shared::kRtBindingCacheSamples, kRtCacheSamples)
      .reads(kRtCacheAccum, Usage::StorageRead)
      .bufferOut(shared::kRtBindingCacheAccum, kRtCacheAccum)
      .push(push_)
      .dispatch(std::max(entries, push_.sampleCount), 1, 1, 64, 1, 1)
      .add(graph);
  ComputePass(in.device, "rt.cache.resolve", "rt/cache_resolve.comp")
      .bufferIn(shared::kRtBindingCacheAccum, kRtCacheAccum)
      .reads(kRtCacheEntries, Usage::StorageRead)
      .bufferOut(shared::kRtBindingCacheEntries, kRtCacheEntries)
      .push(push_)
      .dispatch(entries, 1, 1, 64, 1, 1)
      .add(graph);
}

uint32_t RtRadianceCache::temporalWindow(uint32_t frames) const {
  if (!active_) return frames;
  return std::min(frames, std::max(2u, age_ / 2u));
}

std::vector<std::pair<std::string, double>> RtRadianceCache::figures() const {
  return {{"cacheActive", active_ ? 1.0 : 0.0},
          {"cacheAddedShare", measured_.addedShare()},
          {"cacheEndedShare", measured_.endedShare()},
          {"cacheOffScreenShare", measured_.offScreenShare()},
          {"cachePaths", double(measured_.paths)}};
}

}  // namespace tl::lighting
