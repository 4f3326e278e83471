#include "lighting/common/blas_refit.h"

#include <algorithm>
#include <cstddef>
#include <numeric>

namespace tl::lighting {
namespace {

// SplitMix64: a fixed-seed draw per frame, so runs (and tests) repeat.
uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

float RefitScheduler::priority(uint32_t mesh) const {
  auto it = priority_.find(mesh);
  return it == priority_.end() ? 0.0f : it->second;
}

std::vector<uint32_t> RefitScheduler::choose(const std::vector<RefitCandidate>& stale, const RefitPolicy& policy,
                                             uint64_t frame) {
  for (const auto& c : stale) priority_[c.mesh] += gain(c);
  std::vector<size_t> order(stale.size());
  std::iota(order.begin(), order.end(), 0);
  // Highest priority first; ties by mesh index so the choice is deterministic.
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const float pa = priority_[stale[a].mesh], pb = priority_[stale[b].mesh];
    return pa != pb ? pa > pb : stale[a].mesh < stale[b].mesh;
  });
  std::vector<uint32_t> chosen;
  uint64_t vertices = 0;
  auto take = [&](const RefitCandidate& c) {
    if (!chosen.empty() && vertices + c.vertices > policy.vertexBudget) return false;
    chosen.push_back(c.mesh);
    vertices += c.vertices;
    return true;
  };
  const size_t top = std::min<size_t>(policy.top, order.size());
  for (size_t i = 0; i < top; ++i) take(stale[order[i]]);
  // The random others: a partial Fisher-Yates shuffle of the rest.
  std::vector<size_t> rest(order.begin() + std::ptrdiff_t(top), order.end());
  uint64_t state = mix(frame);
  for (size_t i = 0; i < rest.size() && i < policy.random; ++i) {
    state = mix(state);
    std::swap(rest[i], rest[i + state % (rest.size() - i)]);
    take(stale[rest[i]]);
  }
  for (uint32_t m : chosen) priority_[m] = 0.0f;
  return chosen;
}

}  // namespace tl::lighting
