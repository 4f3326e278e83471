// Redeferred shading (lighting/common/redeferred_pass.h) at full rate against the deferred
// composite: the same image within 1e-3 relative, on every content scene and every
// rasterising path (the reference computes its own image and ignores the setting). Small
// images and two frames each (the second continues the paths' and the many-lights
// accumulation), each mode from a reset history and frame 0, so both see the same samples.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/redeferred_pass.h"

#include <algorithm>
#include <filesystem>
#include <vector>

namespace tl::test {
namespace {

std::vector<std::filesystem::path> contentScenes() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(TWINLIGHT_CONTENT_DIR)) {
    const auto ext = e.path().extension();
    if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<float> renderHdr(session::Session& s, bool redeferred) {
  s.settings().redeferred = redeferred;
  s.resetHistory();
  s.setFrameIndex(0);
  s.renderFrames(2);
  const auto t = s.buffer(lighting::kCompositeHdr).texels();
  return std::vector<float>(t.begin(), t.end());
}

// sum |a - b| / sum |b| over the RGB channels, and the largest per-pixel difference against the
// pixel's luminance-scale value plus the image's mean (so black pixels do not dominate).
struct Difference {
  double relative = 0.0, worstPixel = 0.0;
};
Difference difference(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < b.size(); ++i)
    if (i % 4 != 3) diff += std::abs(double(a[i]) - b[i]), sum += std::abs(double(b[i]));
  const double mean = sum / double(b.size() / 4 * 3);
  Difference d;
  d.relative = sum > 0.0 ? diff / sum : diff;
  for (size_t i = 0; i < b.size(); ++i)
    if (i % 4 != 3) d.worstPixel = std::max(d.worstPixel, std::abs(double(a[i]) - b[i]) / (std::abs(double(b[i])) + mean + 1e-12));
  return d;
}

}  // namespace

TEST_F(GpuTest, RedeferredAtFullRateIsTheDeferredImage) {
  auto& s = session();
  const auto scenes = contentScenes();
  ASSERT_GE(scenes.size(), 15u) << "content scenes not found in " << TWINLIGHT_CONTENT_DIR;
  int compared = 0;
  for (const auto& file : scenes) {
    s.loadScene(file);
    s.setSize(48, 32);
    for (const session::PathInfo& info : s.paths()) {
      if (info.capabilities.isReference || !info.capabilities.rasterizes || !info.available) continue;
      const std::string& path = info.name;
      s.setPath(path);
      const std::vector<float> deferred = renderHdr(s, false);
      const std::vector<float> redeferred = renderHdr(s, true);
      ASSERT_EQ(deferred.size(), redeferred.size());
      const Difference d = difference(redeferred, deferred);
      EXPECT_LE(d.relative, 1e-3) << file.filename() << ", " << path << ": redeferred differs from deferred";
      EXPECT_LE(d.worstPixel, 1e-2) << file.filename() << ", " << path << ": a pixel differs";
      std::printf("redeferred vs deferred  %-22s %-7s relative %.2e  worst pixel %.2e\n", file.filename().string().c_str(),
                  path.c_str(), d.relative, d.worstPixel);
      ++compared;
    }
  }
  EXPECT_GE(compared, int(scenes.size()) * 2);
}

// The I-buffer is in the graph by name (inspector, captures), with its decoder.
TEST_F(GpuTest, RedeferredWritesTheIbuffer) {
  auto& s = session();
  s.setSize(32, 32);
  s.settings().redeferred = true;
  for (const char* n : lighting::kIbuffer) s.requestBuffer(n);
  s.renderFrames(1);
  for (const char* n : lighting::kIbuffer) {
    ASSERT_TRUE(s.hasBuffer(n)) << n;
    const auto t = s.buffer(n).texels();
    EXPECT_EQ(countNonFinite(std::vector<float>(t.begin(), t.end())), 0u) << n;
  }
  // The cornell box is lit: the diffuse sum is positive somewhere.
  const auto dg = s.buffer(lighting::kIbuffer[0]).texels();
  EXPECT_GT(*std::max_element(dg.begin(), dg.end()), 0.0f);
}

}  // namespace tl::test
