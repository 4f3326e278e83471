#include "lighting/rt/blue_noise.h"

#include <cmath>
#include <random>

namespace tl::lighting {
namespace {

// Energy of every texel from a toroidal Gaussian splat of each "on" texel (sigma 1.5, the
// value of the original paper); a void is a minimum among off texels, a cluster a maximum
// among on texels.
class EnergyField {
 public:
  explicit EnergyField(uint32_t size) : size_(size), energy_(size * size, 0.0f), kernel_(size * size) {
    const float sigma = 1.5f;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        float dx = float(std::min(x, size - x)), dy = float(std::min(y, size - y));
        kernel_[y * size + x] = std::exp(-(dx * dx + dy * dy) / (2.0f * sigma * sigma));
      }
  }
  void splat(uint32_t index, float sign) {
    const uint32_t px = index % size_, py = index / size_;
    for (uint32_t y = 0; y < size_; ++y) {
      const uint32_t ky = (y + size_ - py) % size_;
      for (uint32_t x = 0; x < size_; ++x) energy_[y * size_ + x] += sign * kernel_[ky * size_ + (x + size_ - px) % size_];
    }
  }
  // The highest-energy texel with pattern == want (cluster), or the lowest (void).
  uint32_t extreme(const std::vector<uint8_t>& pattern, uint8_t want, bool highest) const {
    uint32_t best = 0;
    float bestEnergy = highest ? -1e30f : 1e30f;
    for (uint32_t i = 0; i < energy_.size(); ++i) {
      if (pattern[i] != want) continue;
      if (highest ? energy_[i] > bestEnergy : energy_[i] < bestEnergy) bestEnergy = energy_[i], best = i;
    }
    return best;
  }

 private:
  uint32_t size_;
  std::vector<float> energy_;
  std::vector<float> kernel_;
};

}  // namespace

std::vector<uint16_t> voidAndClusterRanks(uint32_t size, uint32_t seed) {
  const uint32_t n = size * size;
  std::mt19937 rng(seed);
  // Initial binary pattern: 10% of the texels, then swap the tightest cluster into the
  // largest void until that stops changing anything.
  std::vector<uint8_t> pattern(n, 0);
  EnergyField field(size);
  const uint32_t ones = std::max(1u, n / 10);
  for (uint32_t placed = 0; placed < ones;) {
    uint32_t i = rng() % n;
    if (!pattern[i]) pattern[i] = 1, field.splat(i, 1.0f), ++placed;
  }
  for (uint32_t iteration = 0; iteration < 4 * n; ++iteration) {
    uint32_t cluster = field.extreme(pattern, 1, true);
    pattern[cluster] = 0;
    field.splat(cluster, -1.0f);
    uint32_t hole = field.extreme(pattern, 0, false);
    pattern[hole] = 1;
    field.splat(hole, 1.0f);
    if (hole == cluster) break;
  }

  std::vector<uint16_t> rank(n, 0);
  // Phase 1: remove the tightest clusters of a copy, ranking downwards from ones - 1.
  {
    std::vector<uint8_t> p = pattern;
    EnergyField f = field;
    for (uint32_t r = ones; r-- > 0;) {
      uint32_t cluster = f.extreme(p, 1, true);
      p[cluster] = 0;
      f.splat(cluster, -1.0f);
      rank[cluster] = uint16_t(r);
    }
  }
  // Phases 2 and 3: fill the largest voids, ranking upwards.
  for (uint32_t r = ones; r < n; ++r) {
    uint32_t hole = field.extreme(pattern, 0, false);
    pattern[hole] = 1;
    field.splat(hole, 1.0f);
    rank[hole] = uint16_t(r);
  }
  return rank;
}

}  // namespace tl::lighting
