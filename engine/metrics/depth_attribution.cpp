#include "metrics/depth_attribution.h"

#include "metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tl::metrics {
namespace {

// Mean Rec. 709 luminance of each tile (tiles at the right and bottom edges may be smaller).
std::vector<double> tileLuminance(const Image& image, uint32_t tile) {
  const uint32_t tx = (image.width + tile - 1) / tile, ty = (image.height + tile - 1) / tile;
  std::vector<double> sum(size_t(tx) * ty, 0.0), count(sum.size(), 0.0);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const double luminance = image.channels >= 3 ? 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) +
                                                         0.0722 * image.at(x, y, 2)
                                                   : image.at(x, y, 0);
      const size_t t = size_t(y / tile) * tx + x / tile;
      if (std::isfinite(luminance)) sum[t] += luminance;
      count[t] += 1.0;
    }
  for (size_t t = 0; t < sum.size(); ++t) sum[t] /= std::max(count[t], 1.0);
  return sum;
}

}  // namespace

double DepthAttribution::capturedFrom(size_t from) const {
  double light = 0.0, held = 0.0;
  for (size_t g = from; g < groupShare.size(); ++g) light += groupShare[g], held += groupShare[g] - missing[g];
  return light > 0.0 ? held / light : std::numeric_limits<double>::quiet_NaN();
}

DepthAttribution attributeDepths(const Image& test, const std::vector<Image>& groups, uint32_t tile) {
  if (groups.empty()) throw std::invalid_argument("depth attribution needs at least one depth group");
  if (tile == 0) throw std::invalid_argument("depth attribution: the tile must be at least one pixel");
  for (const Image& g : groups) requireSameSize(test, g);
  const std::vector<double> path = tileLuminance(test, tile);
  std::vector<std::vector<double>> group;
  for (const Image& g : groups) group.push_back(tileLuminance(g, tile));

  const size_t n = groups.size();
  std::vector<double> light(n, 0.0), held(n, 0.0);
  double whole = 0.0, excess = 0.0;
  for (size_t t = 0; t < path.size(); ++t) {
    // The path's light in this tile pays for the groups in depth order.
    double below = 0.0;  // the reference's light of the groups before g
    const double p = std::max(path[t], 0.0);
    for (size_t g = 0; g < n; ++g) {
      const double b = std::max(group[g][t], 0.0);
      light[g] += b;
      held[g] += std::clamp(p - below, 0.0, b);
      below += b;
    }
    whole += below;
    excess += std::max(p - below, 0.0);
  }
  DepthAttribution a;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t g = 0; g < n; ++g) {
    a.captured.push_back(light[g] > 0.0 ? held[g] / light[g] : nan);
    a.missing.push_back(whole > 0.0 ? (light[g] - held[g]) / whole : 0.0);
    a.groupShare.push_back(whole > 0.0 ? light[g] / whole : 0.0);
  }
  a.excess = whole > 0.0 ? excess / whole : 0.0;
  return a;
}

}  // namespace tl::metrics
