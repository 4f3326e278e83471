// A helmet-like asset (content/helmet.glb: every PBR texture inside the .glb, a normal map
// without tangents, an occlusion texture, an emissive visor) renders the same way in every
// path: over the shell's pixels each path's image has the reference's mean and its pattern
// (the per-pixel correlation with the reference, over the whole surface and over its detail:
// the paint, the bare-metal band, the seams and rivets the normal map and the occlusion texture
// draw), and the visor its glow. A path that dropped a texture or the normal map would keep the
// mean and lose the correlation; one that lost light, the mean.
#include "gpu_fixture.h"

#include "../common/test_scenes.h"

#include <cmath>
#include <cstdio>
#include <map>

namespace tl::test {
namespace {

using HelmetTest = RayTracingTest;

// Luminance per shell pixel, in image order: the painted and bare-metal surface, and the
// emissive visor (its glow would dominate a correlation over both); and the surface's detail,
// its luminance less the mean of its 3x3 neighbours, where those are surface too (the seams,
// rivets and band edges the textures and the normal map draw, without the broad shading).
struct ShellImage {
  std::vector<double> surface, visor, detail;
};

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / double(v.size());
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean(a), mb = mean(b);
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

TEST_F(HelmetTest, EveryPathRendersTheHelmetAsTheReferenceDoes) {
  auto& s = session();
  const uint32_t width = 128, height = 96;
  std::map<std::string, ShellImage> images;
  std::vector<uint8_t> shellMask;
  for (const char* path : {"reference", "direct", "legacy", "rt"}) {
    SCOPED_TRACE(path);
    s.loadScene(contentFile("helmet.glb"));
    ASSERT_TRUE(s.scene().ignored.empty()) << s.scene().ignored.front();
    ASSERT_TRUE(s.scene().warnings.empty()) << s.scene().warnings.front();
    s.settings().referenceSamplesPerFrame = 16;
    const uint32_t frames = std::string(path) == "reference" ? 16 : std::string(path) == "direct" ? 1 : 24;
    renderFresh(s, path, width, height, frames, {"gbuffer.instanceId", "gbuffer.emissive"});
    const auto radiance = s.buffer(finalImageOf(path)).texels();
    if (shellMask.empty()) {  // 1: surface, 2: visor; from the first path's G-buffer, for all
      const auto ids = s.buffer("gbuffer.instanceId").texels();
      const auto glow = s.buffer("gbuffer.emissive").texels();
      const uint32_t shell = instanceIdOf(s.scene(), "shell");
      shellMask.resize(ids.size());
      for (size_t p = 0; p < ids.size(); ++p)
        shellMask[p] = uint32_t(ids[p]) != shell ? 0 : glow[4 * p] + glow[4 * p + 1] + glow[4 * p + 2] > 0.0f ? 2 : 1;
    }
    ShellImage& out = images[path];
    const auto lum = [&](size_t p) {
      return 0.2126 * radiance[4 * p] + 0.7152 * radiance[4 * p + 1] + 0.0722 * radiance[4 * p + 2];
    };
    for (size_t p = 0; p < shellMask.size(); ++p) {
      if (shellMask[p] == 1) out.surface.push_back(lum(p));
      if (shellMask[p] == 2) out.visor.push_back(lum(p));
    }
    for (uint32_t y = 1; y + 1 < height; ++y)
      for (uint32_t x = 1; x + 1 < width; ++x) {
        double around = 0.0;
        bool inside = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const size_t q = size_t(y + dy) * width + (x + dx);
            inside &= shellMask[q] == 1;
            around += lum(q);
          }
        if (inside) out.detail.push_back(lum(size_t(y) * width + x) - around / 9.0);
      }
  }
  const ShellImage& truth = images["reference"];
  ASSERT_GT(truth.surface.size(), 1500u) << "the shell fills the view";
  ASSERT_GT(truth.visor.size(), 100u) << "the visor faces the camera";
  for (const char* path : {"direct", "legacy", "rt"}) {
    const ShellImage& got = images[path];
    ASSERT_EQ(got.surface.size(), truth.surface.size()) << path;
    const double ratio = mean(got.surface) / mean(truth.surface);
    const double r = correlation(got.surface, truth.surface);
    const double visor = mean(got.visor) / mean(truth.visor);
    const double detail = correlation(got.detail, truth.detail);
    std::printf("[ helmet   ] %-7s surface: mean / reference %.4f, correlation %.4f (%zu pixels), detail %.4f (%zu); "
                "visor %.4f (%zu)\n",
                path, ratio, r, truth.surface.size(), detail, truth.detail.size(), visor, truth.visor.size());
    RecordProperty(std::string(path) + "_mean_ratio", std::to_string(ratio));
    RecordProperty(std::string(path) + "_detail_correlation", std::to_string(detail));
    // rt carries the ground's bounce; direct (sky and sun only) and legacy (voxel GI) miss up to
    // 7% of it on the shell's lower half (measured 0.944 and 0.930, rt 0.996).
    EXPECT_NEAR(ratio, 1.0, std::string(path) == "rt" ? 0.03 : 0.10) << path;
    // With the reference's normal map switched off these fell to 0.967 and 0.907 (0.9988 and
    // 0.9930 with it).
    EXPECT_GT(r, 0.99) << path;
    EXPECT_GT(detail, 0.97) << path;
    EXPECT_NEAR(visor, 1.0, 0.05) << path;
  }
}

}  // namespace
}  // namespace tl::test
