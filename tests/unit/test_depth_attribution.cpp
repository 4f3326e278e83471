// Per-bounce attribution (metrics/depth_attribution.h) on images with known answers.
#include "metrics/depth_attribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tl::metrics {
namespace {

// A grey image (equal channels, so luminance = value) of w x h with value f(x, y).
template <class F>
Image grey(uint32_t w, uint32_t h, F f) {
  Image img = Image::filled(w, h, 3, 0.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t c = 0; c < 3; ++c) img.at(x, y, c) = f(x, y);
  return img;
}

Image sum(const std::vector<Image>& parts, size_t count) {
  Image s = Image::filled(parts[0].width, parts[0].height, 3, 0.0f);
  for (size_t g = 0; g < count; ++g)
    for (size_t i = 0; i < s.data.size(); ++i) s.data[i] += parts[g].data[i];
  return s;
}

// Four depth groups that vary across the image, as a room's would.
std::vector<Image> groups(uint32_t w, uint32_t h) {
  return {grey(w, h, [](uint32_t x, uint32_t) { return 0.5f + 0.01f * float(x); }),
          grey(w, h, [](uint32_t, uint32_t y) { return 0.3f + 0.02f * float(y); }),
          grey(w, h, [](uint32_t x, uint32_t y) { return 0.1f + 0.001f * float(x * y); }),
          grey(w, h, [](uint32_t, uint32_t) { return 0.2f; })};
}

TEST(DepthAttribution, TheReferenceCapturesEverythingAndNothingMore) {
  const auto g = groups(32, 24);
  const DepthAttribution a = attributeDepths(sum(g, 4), g);
  double shares = 0.0;
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(a.captured[k], 1.0, 1e-6) << k;
    EXPECT_NEAR(a.missing[k], 0.0, 1e-6) << k;
    shares += a.groupShare[k];
  }
  EXPECT_NEAR(shares, 1.0, 1e-9);
  EXPECT_NEAR(a.excess, 0.0, 1e-6);
  EXPECT_NEAR(a.capturedFrom(2), 1.0, 1e-6);
}

// An image that holds exactly the reference truncated after k groups (what --bounces k renders
// for k < 4) captures those groups whole and none of the rest.
TEST(DepthAttribution, ATruncatedReferenceCapturesItsGroups) {
  const auto g = groups(32, 24);
  for (size_t k = 1; k < 4; ++k) {
    const DepthAttribution a = attributeDepths(sum(g, k), g);
    for (size_t j = 0; j < 4; ++j) EXPECT_NEAR(a.captured[j], j < k ? 1.0 : 0.0, 1e-6) << "k " << k << " group " << j;
    EXPECT_NEAR(a.excess, 0.0, 1e-6);
  }
}

// Half of the second bounce on top of the first two groups: 50% of it, none of the rest; the
// missing light is the half of the second bounce and all of the third-and-more.
TEST(DepthAttribution, PartOfAGroupIsItsShare) {
  const auto g = groups(32, 24);
  Image test = sum(g, 2);
  for (size_t i = 0; i < test.data.size(); ++i) test.data[i] += 0.5f * g[2].data[i];
  const DepthAttribution a = attributeDepths(test, g);
  EXPECT_NEAR(a.captured[2], 0.5, 1e-6);
  EXPECT_NEAR(a.captured[3], 0.0, 1e-6);
  EXPECT_NEAR(a.missing[2], 0.5 * a.groupShare[2], 1e-6);
  EXPECT_NEAR(a.missing[3], a.groupShare[3], 1e-6);
  const double rest = (0.5 * a.groupShare[2]) / (a.groupShare[2] + a.groupShare[3]);
  EXPECT_NEAR(a.capturedFrom(2), rest, 1e-6);
}

// The decomposition is exact: mean(test) / mean(reference) = 1 - sum(missing) + excess, over
// tiles, for any image (here noise well above and below the reference in places).
TEST(DepthAttribution, MissingAndExcessAddUpToTheMeanRatio) {
  const auto g = groups(32, 24);
  const Image reference = sum(g, 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  Image test = reference;
  for (size_t i = 0; i < test.data.size(); i += 3) {
    const float k = u(rng);
    for (int c = 0; c < 3; ++c) test.data[i + c] *= k;
  }
  const DepthAttribution a = attributeDepths(test, g, 1);  // 1-pixel tiles: the ratio of pixel sums
  double t = 0.0, r = 0.0, missing = 0.0;
  for (size_t i = 0; i < test.data.size(); i += 3) t += test.data[i], r += reference.data[i];
  for (double m : a.missing) missing += m;
  EXPECT_NEAR(t / r, 1.0 - missing + a.excess, 1e-6);
  EXPECT_GT(a.excess, 0.05);
  EXPECT_GT(missing, 0.05);
}

// Tiles: light moved within a tile is still credited; light moved across tiles is not.
TEST(DepthAttribution, LightIsCreditedWithinATileOnly) {
  const uint32_t w = 16, h = 8;
  const std::vector<Image> g = {grey(w, h, [](uint32_t, uint32_t) { return 1.0f; })};
  // All of each 8x8 tile's light gathered into its first column: captured in full.
  const Image within = grey(w, h, [](uint32_t x, uint32_t) { return x % 8 == 0 ? 8.0f : 0.0f; });
  EXPECT_NEAR(attributeDepths(within, g).captured[0], 1.0, 1e-6);
  // The left tile's light moved into the right tile: half captured, the other half excess.
  const Image across = grey(w, h, [](uint32_t x, uint32_t) { return x < 8 ? 0.0f : 2.0f; });
  const DepthAttribution a = attributeDepths(across, g);
  EXPECT_NEAR(a.captured[0], 0.5, 1e-6);
  EXPECT_NEAR(a.excess, 0.5, 1e-6);
}

TEST(DepthAttribution, AnEmptyGroupHasNoShare) {
  const uint32_t w = 8, h = 8;
  const std::vector<Image> g = {grey(w, h, [](uint32_t, uint32_t) { return 1.0f; }),
                                grey(w, h, [](uint32_t, uint32_t) { return 0.0f; })};
  const DepthAttribution a = attributeDepths(g[0], g);
  EXPECT_NEAR(a.captured[0], 1.0, 1e-9);
  EXPECT_TRUE(std::isnan(a.captured[1]));
  EXPECT_THROW(attributeDepths(g[0], {}), std::invalid_argument);
  EXPECT_THROW(attributeDepths(Image::filled(4, 4, 3, 0.0f), g), std::invalid_argument);
}

}  // namespace
}  // namespace tl::metrics
