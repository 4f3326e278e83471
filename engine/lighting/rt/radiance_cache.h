// The RT path's world-space radiance cache (shared/rt_cache.h): the graph resources, the
// decision whether it runs this frame (measured, not a flag), its history policy and the
// accumulate and resolve passes. The update paths are a ray-tracing pass of the RT path
// (rt_path.cpp), since they shade hits as its hit lighting does.
#pragma once

#include "graph/graph.h"
#include "gpu/pipeline.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/frame_key.h"
#include "shared/rt.h"
#include "shared/rt_cache.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

namespace tl::lighting {

inline constexpr graph::BufferName kRtCacheEntries{"rt.cache.entries"};    // persistent: what hits read
inline constexpr graph::BufferName kRtCacheAccum{"rt.cache.accum"};        // persistent: keys and sums
inline constexpr graph::BufferName kRtCacheSamples{"rt.cache.samples"};    // the update paths' samples
inline constexpr graph::BufferName kRtCacheOutcomes{"rt.cache.outcomes"};  // each path's first ray: shared::RtCacheOutcome

// What the update paths' first rays found in one frame, and the light involved.
struct RtCacheOutcomes {
  uint32_t paths = 0;      // paths that started (their pixel is not sky)
  uint32_t sky = 0;
  uint32_t onScreen = 0;
  uint32_t offScreen = 0;
  uint32_t ended = 0;      // rays whose length ran out inside the scene
  double gathered = 0.0;   // luminance the GI rays bring back without the cache (summed)
  double added = 0.0;      // luminance the cache adds to it at hits off screen (summed)
  double offScreenShare() const { return paths ? double(offScreen) / double(paths) : 0.0; }
  // The share of the bounced light that only the cache brings: what it changes.
  double addedShare() const { return gathered + added > 0.0 ? added / (gathered + added) : 0.0; }
  // Rays that end inside the scene bring back nothing but the cache's light.
  double endedShare() const { return paths ? double(ended) / double(paths) : 0.0; }
  // What decides whether the cache runs: the larger of the two.
  double cacheGain() const { return std::max(addedShare(), endedShare()); }
};
// Sums rt.cache.outcomes' bytes (one shared::RtCacheOutcome each).
RtCacheOutcomes countCacheOutcomes(std::span<const uint8_t> bytes);

// Whether the cache runs, from what it changes: on while the light it adds is at least
// `minGain` of the bounced light, off below half of that (no flicker on the edge). It starts
// off: the first frame's probe paths measure, the next decides.
class RtCacheSwitch {
 public:
  bool update(const RtCacheOutcomes& measured, float minGain);
  bool on() const { return on_; }

 private:
  bool on_ = false;
};

// Which frame-key parts drop the cache: what its light depends on. The camera does not (it
// is in world space); moving geometry does not (cells follow through their bounded history).
inline constexpr FrameParts kRtCacheRestarts =
    parts(FramePart::Scene, FramePart::Settings, FramePart::Sun, FramePart::Sky, FramePart::Albedo);

class RtRadianceCache {
 public:
  // This frame's plan: whether the cache runs (from the last frame's outcomes) or only its
  // probe paths measure, whether it restarts; fills the cache's fields of `push` and
  // requests this frame's outcomes. Call before any pass that reads the cache.
  void plan(graph::RenderGraph& graph, FrameInputs& in, shared::RtPush& push, float maxEmitterRadiance);
  bool active() const { return active_; }  // the cache is read and written this frame
  bool restart() const { return restart_; }
  // Frames the cache has run since it last started over (0: this frame starts it).
  uint32_t age() const { return age_; }
  // The RT path's temporal window (`frames` at most) while the cache runs: samples taken while
  // it was warming up (its light still rising bounce by bounce from a cold start) are kept
  // for at most half its age, so the image does not average in the first, darker frames.
  uint32_t temporalWindow(uint32_t frames) const;
  uint32_t paths(const FrameInputs& in) const { return tilesX(in) * tilesY(in); }
  uint32_t tilesX(const FrameInputs& in) const { return (in.settings.width + tile_ - 1) / tile_; }
  uint32_t tilesY(const FrameInputs& in) const { return (in.settings.height + tile_ - 1) / tile_; }
  graph::ResourceDesc samplesDesc(const FrameInputs& in) const;
  graph::ResourceDesc outcomesDesc(const FrameInputs& in) const;

  // rt.cache.accumulate and rt.cache.resolve (only when active).
  void addPasses(graph::RenderGraph& graph, FrameInputs& in);

  std::vector<std::pair<std::string, double>> figures() const;

 private:
  RtCacheSwitch switch_;
  uint64_t switchScene_ = 0;  // the frame key's scene hash the switch's measurements belong to
  HistoryKeeper history_;
  bool active_ = false, wasActive_ = false, restart_ = false;
  uint32_t tile_ = 8, bounces_ = 3;
  uint32_t frame_ = 0;  // the cache's own frame count: the parity of its sums
  uint32_t age_ = 0;
  shared::RtCachePush push_{};
  RtCacheOutcomes measured_;
  // Outcomes read back, until the frame kOutcomeLag later (in this path's frames) decides from them.
  static constexpr uint64_t kOutcomeLag = gpu::kMaxFramesInFlight;
  std::map<uint64_t, RtCacheOutcomes> outcomes_;   // by this path's own frame number
  std::map<uint64_t, uint64_t> ownFrames_;           // the session's frame -> this path's
  uint64_t ownFrame_ = 0;       // frames this path planned since the switch started over
  uint64_t switchResets_ = 0;   // FrameInputs::historyResets the switch's measurements belong to
};

}  // namespace tl::lighting
