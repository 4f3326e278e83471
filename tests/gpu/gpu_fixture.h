// One Session (device + validation layers) shared by the GPU tests of a binary: creating
// a device with validation costs more than most tests. Every test checks that the layers
// reported nothing.
#pragma once

#include "session/session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace tl::test {

inline std::filesystem::path contentFile(const char* name) { return std::filesystem::path(TWINLIGHT_CONTENT_DIR) / name; }

class GpuTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!session_) {
      gpu::DeviceOptions o;
      o.validation = true;
      session_ = std::make_unique<session::Session>(o);
    }
  }
  // Destroyed before main returns: at static-destruction time the Vulkan loader and the
  // validation layer may already be gone.
  static void TearDownTestSuite() { session_.reset(); }
  static session::Session& session() { return *session_; }
  void TearDown() override {
    EXPECT_EQ(session_->validationErrors(), errorsBefore_) << "Vulkan validation reported errors during this test";
  }
  void SetUp() override { errorsBefore_ = session_->validationErrors(); }

  static inline std::unique_ptr<session::Session> session_;
  uint32_t errorsBefore_ = 0;
};

// Tests that need ray tracing: skipped where the device has none; each leaves the shared
// session on the direct path with default settings.
class RayTracingTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (!session().device().rayTracing().pipeline) GTEST_SKIP() << session().device().rayTracing().unavailableReason;
  }
  void TearDown() override {
    session().setPath("direct");
    session().settings() = lighting::RenderSettings{};
    GpuTest::TearDown();
  }
};

// Counts non-finite values among decoded texels.
inline size_t countNonFinite(const std::vector<float>& v) {
  size_t n = 0;
  for (float x : v) n += !std::isfinite(x);
  return n;
}

}  // namespace tl::test
