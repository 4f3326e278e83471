// Per-bounce attribution: which part of each group of path depths an image holds, measured
// against the reference's radiance split by depth (lighting/reference/reference_path.h,
// referenceBounceBuffers). A path that is not split by depth is credited in depth order: in
// each tile its light first pays for the reference's shallowest light, then the next group's,
// and so on; what is left over is excess. docs/accuracy.md ("Per-bounce attribution") gives
// the definition and why it is taken per tile.
#pragma once

#include "metrics/image.h"

#include <vector>

namespace tl::metrics {

// Side of the square tiles (pixels) whose mean luminance is attributed: large enough that pixel
// noise mostly averages out (noise would otherwise read as missing and excess light at once),
// small enough that a path cannot pay for light it misses in one part of the image with light
// it adds in another.
inline constexpr uint32_t kAttributionTile = 8;

struct DepthAttribution {
  // Per group: the share of the group's light (sum over tiles of its luminance) the image holds
  // (0..1; NaN when the group holds no light).
  std::vector<double> captured;
  // Per group: the light of the group the image lacks, as a fraction of the reference's whole
  // light: the error the group contributes to the mean.
  std::vector<double> missing;
  // Light the image holds beyond the reference's whole, as a fraction of the whole.
  double excess = 0.0;
  // Per group: the group's share of the reference's whole light.
  std::vector<double> groupShare;
  // The captured share of groups `from` onwards together (NaN when they hold no light).
  double capturedFrom(size_t from) const;
};

// `groups`: the reference's radiance by depth group, shallowest first, each the image's size
// (RGB); their sum is the reference. The mean ratio decomposes exactly:
// mean(test) / mean(reference) = 1 - sum(missing) + excess (luminance, over tiles).
DepthAttribution attributeDepths(const Image& test, const std::vector<Image>& groups, uint32_t tile = kAttributionTile);

}  // namespace tl::metrics
