// One Session (device + validation layers) shared by every GPU test of the binary: creating
// a device with validation costs more than most tests. Every test checks that the layers
// reported nothing, starts from the same baseline and leaves the session in it, so the
// tests pass in any order in one process (`tl_gpu_tests --gtest_shuffle`).
#pragma once

#include "lighting/common/composite_pass.h"
#include "session/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace tl::test {

inline std::filesystem::path contentFile(const char* name) { return std::filesystem::path(TWINLIGHT_CONTENT_DIR) / name; }

// The state every GPU test starts from and is returned to afterwards: content/cornell.gltf
// loaded (its camera and its light, the default sun size and no environment map, no history, no
// albedo edits, animation at 0), the direct
// path, default settings (and size), no display request, compare view, reopened capture or
// albedo database, the animation still, frame index 0. Everything a test can change through
// the Session is on this list.
inline void restoreBaseline(session::Session& s) {
  s.setCompareView(std::nullopt);
  s.setDisplay(std::nullopt);
  if (s.hasCapture()) s.closeCapture();
  s.closeAlbedoDatabase();
  s.settings() = lighting::RenderSettings{};
  s.setPath("direct");
  s.setAnimationStep(0.0);
  s.setFramesInFlight(gpu::kMaxFramesInFlight);
  // What a scene load keeps (the sun's angular size, an environment map, its rotation and
  // intensity) back to the defaults; the load sets the rest from the file.
  s.setLighting(session::Lighting{});
  s.loadScene(contentFile("cornell.gltf"));  // also resets the scene's lighting, view, history, albedo edits, animation time
  s.setFrameIndex(0);
}

// The named figure of the last frame's path (Session::pathFigures); a missing one fails the test.
inline double pathFigure(const session::Session& s, const std::string& name) {
  for (const auto& [n, v] : s.pathFigures())
    if (n == name) return v;
  ADD_FAILURE() << "no figure " << name;
  return -1.0;
}

// The buffer a path's final HDR image is in: the reference's own estimate, else the composite.
inline std::string_view finalImageOf(const std::string& path) {
  return path == "reference" ? std::string_view("reference.radiance") : lighting::kCompositeHdr.name();
}

// Renders `frames` frames of `path` at width x height from a fresh history (frame index 0) and
// reads the final image and `buffers` back from the last one.
inline void renderFresh(session::Session& s, const std::string& path, uint32_t width, uint32_t height, uint32_t frames,
                        std::initializer_list<const char*> buffers = {}) {
  s.setPath(path);
  s.setSize(width, height);
  s.setFrameIndex(0);
  s.resetHistory();
  s.renderFrames(frames - 1);
  s.requestBuffer(finalImageOf(path));
  for (const char* b : buffers) s.requestBuffer(b);
  s.renderFrames(1);
}

// The mean RGB of each instance's pixels of `image` away from its edges (all 8 neighbours on the
// same instance in gbuffer.instanceId, which the last frame read back: no pixel mixes in what
// lies beside it), by instance name, and how many pixels made it.
struct InstanceMean {
  glm::dvec3 rgb{0.0};
  size_t pixels = 0;
};
inline std::map<std::string, InstanceMean> interiorMeanByInstance(const session::Session& s, std::string_view image) {
  const auto& readback = s.buffer(image);
  const auto texels = readback.texels();
  const uint32_t channels = readback.channels(), width = readback.extent.width, height = readback.extent.height;
  const auto ids = s.buffer("gbuffer.instanceId").texels();
  std::map<std::string, InstanceMean> means;
  for (uint32_t y = 1; y + 1 < height; ++y)
    for (uint32_t x = 1; x + 1 < width; ++x) {
      const float id = ids[size_t(y) * width + x];
      if (id == 0.0f) continue;
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside &= ids[size_t(int(y) + dy) * width + size_t(int(x) + dx)] == id;
      if (!inside) continue;
      const size_t p = (size_t(y) * width + x) * channels;
      auto& m = means[s.scene().instances[size_t(id) - 1].name];
      m.rgb += glm::dvec3(texels[p], texels[p + 1], texels[p + 2]);
      ++m.pixels;
    }
  for (auto& [name, m] : means) m.rgb /= double(m.pixels);
  return means;
}

// Sum of |a - b| over sum of |b|, over the RGB of two RGBA images: how far image a is from b.
inline double relativeDifferenceRgb(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
    for (int c = 0; c < 3; ++c) diff += std::abs(a[i + c] - b[i + c]), sum += std::abs(b[i + c]);
  return diff / std::max(sum, 1e-12);
}

class GpuTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!session_) {
      gpu::DeviceOptions o;
      o.validation = true;
      session_ = std::make_unique<session::Session>(o);
      restoreBaseline(*session_);
    }
  }
  static session::Session& session() { return *session_; }
  void SetUp() override { errorsBefore_ = session_->validationErrors(); }
  void TearDown() override {
    restoreBaseline(*session_);
    EXPECT_EQ(session_->validationErrors(), errorsBefore_) << "Vulkan validation reported errors during this test";
  }

  static inline std::unique_ptr<session::Session> session_;
  uint32_t errorsBefore_ = 0;

  // Destroys the session after the last test, before main returns: at static-destruction
  // time the Vulkan loader and the validation layer may already be gone.
  struct SessionEnvironment : ::testing::Environment {
    void TearDown() override { session_.reset(); }
  };
  static inline ::testing::Environment* const environment_ = ::testing::AddGlobalTestEnvironment(new SessionEnvironment);
};

// Tests that need ray tracing: skipped where the device has none.
class RayTracingTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (!session().device().rayTracing().pipeline) GTEST_SKIP() << session().device().rayTracing().unavailableReason;
  }
};

// Counts non-finite values among decoded texels.
inline size_t countNonFinite(const std::vector<float>& v) {
  size_t n = 0;
  for (float x : v) n += !std::isfinite(x);
  return n;
}

}  // namespace tl::test
