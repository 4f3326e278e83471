// Two frames in flight: the host records frame N+1 while the device runs frame N, so
// everything the host writes per frame (the frame constants, the camera-relative instance
// transforms and TLAS instances, the light table and its shadow views) lives in a ring, one
// copy per frame in flight. With the camera moving every frame a shared copy would hand
// frame N frame N+1's camera; the guard is the difference between two neighbouring frames.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"

#include <algorithm>
#include <cmath>

namespace tl::test {
namespace {

constexpr int kFrames = 8;

session::View panned(session::View v, double metres) {
  const glm::dvec3 right = glm::normalize(glm::cross(v.forward, v.up));
  v.position += right * metres;
  return v;
}

struct MovingRender {
  std::vector<std::vector<float>> frames;  // composite.hdr of every frame, in order
  uint32_t mostInFlight = 0;               // the most frames the session had in flight at once
  uint32_t runningAtNextBegin = 0;         // frames the device had not finished when the next one was begun
};

// kFrames frames of `path` on cornell with a point light, the camera panning 2 cm a frame
// (far from a cut: the histories reproject and keep), collected the way the editor does:
// begin a frame, collect the oldest when the limit is reached.
MovingRender renderPanning(session::Session& s, const std::string& path, uint32_t inFlight) {
  s.setFramesInFlight(inFlight);
  session::Lighting lighting = s.lighting();
  scene::Light lamp;
  lamp.name = "lamp";
  lamp.intensity = 4.0f;
  lamp.position = s.view().position + s.view().forward * 1.5;
  lighting.lights = {lamp};
  s.setLighting(lighting);
  s.setPath(path);
  s.setSize(96, 72);
  s.resetHistory();
  s.setFrameIndex(0);
  const session::View start = s.view();
  MovingRender out;
  auto collect = [&] {
    s.finishFrame();
    out.frames.push_back(s.buffer(std::string(lighting::kCompositeHdr)).texels());
  };
  for (int i = 0; i < kFrames; ++i) {
    if (s.framesInFlightNow() >= inFlight) collect();
    s.setView(panned(start, 0.02 * i));
    const bool running = s.frameInFlight() && !s.frameDone();
    s.beginFrame();
    out.runningAtNextBegin += running;
    out.mostInFlight = std::max(out.mostInFlight, s.framesInFlightNow());
  }
  while (s.frameInFlight()) collect();
  s.setView(start);
  return out;
}

double maxAbsDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, double(std::abs(a[i] - b[i])));
  return d;
}

class FramesInFlightTest : public RayTracingTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(FramesInFlightTest, TwoInFlightRenderWhatOneDoesWithTheCameraMovingEveryFrame) {
  auto& s = session();
  const MovingRender one = renderPanning(s, GetParam(), 1);
  const MovingRender two = renderPanning(s, GetParam(), 2);
  EXPECT_EQ(one.mostInFlight, 1u);
  EXPECT_EQ(two.mostInFlight, 2u) << "the session never had two frames in flight";
  ASSERT_EQ(one.frames.size(), size_t(kFrames));
  ASSERT_EQ(two.frames.size(), size_t(kFrames));
  // Every frame, not only the last: a path without history shows a frame that got its
  // neighbour's inputs in that frame alone.
  double neighbour = 1e30, difference = 0.0;
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_EQ(one.frames[i].size(), two.frames[i].size());
    EXPECT_EQ(countNonFinite(two.frames[i]), 0u) << "frame " << i;
    difference = std::max(difference, maxAbsDifference(one.frames[i], two.frames[i]));
    // What a frame would show with its neighbour's inputs: the error this test guards.
    if (i > 0) neighbour = std::min(neighbour, maxAbsDifference(one.frames[i], one.frames[i - 1]));
  }
  std::printf("%s: %u of %d frames still running when the next began\n", GetParam(), two.runningAtNextBegin, kFrames);
  std::printf("%s: neighbouring frames differ by at least %.4g, two in flight from one by at most %.4g\n", GetParam(),
              neighbour, difference);
  RecordProperty("neighbour_difference", std::to_string(neighbour));
  RecordProperty("in_flight_difference", std::to_string(difference));
  ASSERT_GT(neighbour, 1e-3) << "the camera's pan must change every frame for the comparison to mean anything";
  EXPECT_LE(difference, 1e-3 * neighbour);
}

INSTANTIATE_TEST_SUITE_P(Paths, FramesInFlightTest, ::testing::Values("direct", "rt", "legacy", "reference"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace tl::test
