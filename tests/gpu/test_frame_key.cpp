// The frame key: every history decides from the parts of the session's key what it
// keeps. A 0.2 m sideways step restarts the reference (it once kept summing samples of the
// old position: its key held a camera-relative view-projection, blind to translation), and a
// table changes each part once and checks which histories restart, reject or keep, with the
// effect where a buffer shows it (the reference's sample count, rt's and SSAO's frame counts,
// the voxels' rebuild).
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "lighting/legacy/legacy_path.h"
#include "lighting/rt/rt_path.h"

#include <functional>

namespace tl::test {
namespace {

using lighting::FramePart;
using lighting::HistoryAction;

class FrameKeyTest : public RayTracingTest {
 protected:
  void TearDown() override {
    session().setAnimationStep(0.0);
    session().setAnimationTime(0.0);
    RayTracingTest::TearDown();
  }
  double figure(const std::string& name) { return pathFigure(session(), name); }
  // The last frame's decision of `history`, or nothing when it did not run.
  std::optional<lighting::HistoryDecision> decision(const std::string& history) {
    for (const auto& d : session().historyDecisions())
      if (d.history == history) return d;
    return std::nullopt;
  }
};

session::View movedSideways(session::View v, double metres) {
  const glm::dvec3 right = glm::normalize(glm::cross(v.forward, v.up));
  v.position += right * metres;
  return v;
}

TEST_F(FrameKeyTest, MovingTheCameraSidewaysRestartsTheReference) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setPath("reference");
  s.setSize(32, 32);
  s.settings().referenceSamplesPerFrame = 4;
  s.settings().referenceBounces = 3;
  s.resetHistory();
  s.renderFrames(4);
  const double before = figure("reference.samples");
  EXPECT_EQ(before, 16.0);

  // 0.2 m is far from a camera cut on cornell (a fifth of the scene) and turns nothing.
  const session::View moved = movedSideways(s.view(), 0.2);
  s.setView(moved);
  s.setFrameIndex(100);
  s.renderFrames(1);
  const double after = figure("reference.samples");
  std::printf("reference samples per pixel: %.0f before the 0.2 m step, %.0f after the first frame past it\n", before, after);
  RecordProperty("samples_before", std::to_string(before));
  RecordProperty("samples_after", std::to_string(after));
  EXPECT_EQ(after, 4.0) << "the sum must restart at the new position, not add to the old one's 16 samples";
  s.requestBuffer("reference.radiance");
  s.renderFrames(3);
  EXPECT_EQ(figure("reference.samples"), 16.0);
  const std::vector<float> continued = s.buffer("reference.radiance").texels();

  // Restarted means exactly what a fresh render at the new position gives (same device, same
  // frame numbers, so the same random numbers): no sample of the old position is left.
  s.resetHistory();
  s.setFrameIndex(100);
  s.requestBuffer("reference.radiance");
  s.renderFrames(4);
  const std::vector<float> fresh = s.buffer("reference.radiance").texels();
  ASSERT_EQ(continued.size(), fresh.size());
  double worst = 0.0, scale = 0.0;
  for (size_t i = 0; i < fresh.size(); ++i) {
    worst = std::max(worst, double(std::abs(continued[i] - fresh[i])));
    scale = std::max(scale, double(std::abs(fresh[i])));
  }
  EXPECT_LE(worst, 1e-5 * scale) << "the image after the step holds samples from before it";

  // The first frame after the step said why it restarted.
  s.setView(movedSideways(moved, 0.2));
  s.renderFrames(1);
  auto d = decision("reference.accumulation");
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->action, HistoryAction::Restart);
  EXPECT_EQ(d->acted, lighting::partBit(FramePart::CameraPosition)) << lighting::describeParts(d->acted);
}

// Frames rendered before each row's change.
constexpr uint32_t kSettleFrames = 8;

// One change of one part, what it does to the session, and how each history must answer.
struct Row {
  const char* part;
  std::function<void(session::Session&)> change;
  HistoryAction reference, rt, voxels, ssao, taa;
};

// Whether the decision names the row's part among those it acted on.
bool names(const lighting::HistoryDecision& d, const std::string& part) {
  const std::string acted = ", " + lighting::describeParts(d.acted) + ",";
  auto has = [&](const std::string& name) { return acted.find(", " + name + ",") != std::string::npos; };
  if (part.rfind("settings", 0) == 0) return has("settings");  // settings.<path> is the path's settings part
  // The reference does not reproject: a cut is a camera move to it.
  if (part == "camera.cut") return has("camera.cut") || (d.history == "reference.accumulation" && has("camera.position"));
  // TAA's pass is made anew with a new scene: its history starts with nothing to keep.
  if (part == "scene" && d.history == "taa" && d.acted == 0) return true;
  return has(part);
}

TEST_F(FrameKeyTest, EachPartRestartsExactlyTheHistoriesThatDependOnIt) {
  auto& s = session();
  using A = HistoryAction;
  const A keep = A::Keep, reject = A::Reject, restart = A::Restart;
  const std::vector<Row> rows = {
      {"nothing", [](session::Session&) {}, keep, keep, keep, keep, keep},
      {"camera.position", [](session::Session& s) { s.setView(movedSideways(s.view(), 0.2)); }, restart, keep, keep, keep, keep},
      {"camera.orientation",
       [](session::Session& s) {
         session::View v = s.view();
         v.forward = glm::normalize(v.forward + 0.05 * glm::normalize(glm::cross(v.forward, v.up)));
         s.setView(v);
       },
       restart, keep, keep, keep, keep},
      {"camera.cut",  // a jump of a third of the scene
       [](session::Session& s) { s.setView(movedSideways(s.view(), 0.3 * glm::length(s.scene().bounds.size()))); },
       restart, restart, keep, restart, restart},
      {"projection",
       [](session::Session& s) {
         session::View v = s.view();
         v.yfovRadians *= 1.1f;
         s.setView(v);
       },
       restart, keep, keep, keep, keep},
      {"sun",
       [](session::Session& s) {
         session::Lighting l = s.lighting();
         l.sunDirection = glm::normalize(l.sunDirection + glm::dvec3(0.2, 0.0, 0.1));
         s.setLighting(l);
       },
       restart, reject, restart, keep, keep},
      {"sky",
       [](session::Session& s) {
         session::Lighting l = s.lighting();
         l.skyRadiance *= 0.5f;
         s.setLighting(l);
       },
       restart, reject, restart, keep, keep},  // the voxels hold the sky through the screen feedback
      {"scene", [](session::Session& s) { s.loadScene(contentFile("banners.gltf")); }, restart, restart, restart, restart,
       restart},
      {"geometry", [](session::Session& s) { s.setAnimationTime(s.animationTime() + 0.25); }, restart, keep, keep, keep, keep},
      {"albedo", [](session::Session& s) { s.albedo().setOverride(s.albedo().combinationOf(0), glm::vec3(0.9f, 0.2f, 0.1f)); },
       keep, reject, keep, keep, keep},
      {"settings.reference", [](session::Session& s) { s.settings().referenceBounces = 2; }, restart, keep, keep, keep, keep},
      {"settings.rt", [](session::Session& s) { s.settings().rtRayLength = 4.0f; }, keep, restart, keep, keep, keep},
      {"settings.legacy", [](session::Session& s) { s.settings().legacyAoRadius = 0.5f; }, keep, keep, restart, restart, keep},
      // The material override mode is every path's setting: what the surfaces reflect.
      {"settings.materials", [](session::Session& s) { s.settings().materials = lighting::MaterialMode::Clay; }, restart,
       restart, restart, restart, keep},
      {"frame.gap",  // another path renders the frame in between
       [](session::Session& s) {
         const std::string path = s.path();
         s.setPath("direct");
         s.renderFrames(1);
         s.setPath(path);
       },
       keep, keep, keep, keep, restart},
  };

  std::printf("%-20s %-12s %-24s %-8s %s\n", "part changed", "path", "history", "action", "acted on");
  for (const Row& row : rows) {
    for (const char* path : {"reference", "rt", "legacy"}) {
      SCOPED_TRACE(std::string(row.part) + " on " + path);
      // Each row starts from the same state: the scene as loaded, the test's settings.
      s.loadScene(contentFile("banners.gltf"));
      s.setAnimationStep(0.0);
      s.settings() = lighting::RenderSettings{};
      s.setSize(48, 27);
      s.settings().taa = true;
      s.settings().rtFarLegacy = false;        // one legacy path at a time
      s.settings().rtCacheMinGain = 0.0f;     // the radiance cache runs whatever it measures
      s.settings().legacyLevel0Extent = 200;   // one level over the whole scene: it does not follow the camera
      s.settings().legacyMaxLevels = 1;
      s.settings().legacyVoxelResolution = 32;
      s.settings().legacySettleFrames = 0;     // settled voxels are kept, so a rebuild is a decision
      s.setPath(path);
      // Histories built, voxels settled; eight frames, so that rt's window (half the forced-on
      // radiance cache's age while it warms, RtRadianceCache::temporalWindow) holds four.
      s.renderFrames(kSettleFrames);
      row.change(s);
      s.requestBuffer(lighting::kCoCgAo);
      s.requestBuffer(lighting::kLegacySsao);
      s.renderFrames(1);

      std::vector<std::pair<std::string, A>> expected;
      if (std::string(path) == "reference") expected = {{"reference.accumulation", row.reference}};
      // The radiance cache is in world space: only what its light depends on restarts it.
      const std::string part = row.part;
      const bool cacheRestarts = part == "sun" || part == "sky" || part == "scene" || part == "albedo" ||
                                 part == "settings.rt" || part == "settings.materials";
      if (std::string(path) == "rt")
        expected = {{"rt.temporal", row.rt}, {"rt.cache", cacheRestarts ? restart : keep}, {"taa", row.taa}};
      if (std::string(path) == "legacy") expected = {{"legacy.voxels", row.voxels}, {"legacy.ssao", row.ssao}, {"taa", row.taa}};
      ASSERT_EQ(s.historyDecisions().size(), expected.size()) << "every history of the path decides, once";
      for (const auto& [history, action] : expected) {
        auto d = decision(history);
        ASSERT_TRUE(d.has_value()) << history << " did not run";
        std::printf("%-20s %-12s %-24s %-8s %s\n", row.part, path, history.c_str(), lighting::actionName(d->action),
                    lighting::describeParts(d->acted).c_str());
        EXPECT_EQ(lighting::actionName(d->action), std::string(lighting::actionName(action))) << history;
        if (action != keep) {
          EXPECT_TRUE(names(*d, row.part)) << history << " acted on " << lighting::describeParts(d->acted);
        }
      }

      // The effects that buffers and figures show.
      if (std::string(path) == "reference") {
        const double samples = figure("reference.samples");
        EXPECT_EQ(samples, row.reference == restart ? 1.0 : double(kSettleFrames + 1));
      }
      if (std::string(path) == "rt" && row.rt != reject) {
        // Accumulated frames (w) over the surface pixels: 1 after a restart.
        const auto t = s.buffer(lighting::kCoCgAo).texels();
        double sum = 0.0, most = 0.0;
        size_t n = 0;
        for (size_t i = 3; i < t.size(); i += 4)
          if (t[i] > 0.0f) sum += t[i], most = std::max(most, double(t[i])), ++n;
        ASSERT_GT(n, 0u);
        if (row.rt == restart) {
          EXPECT_LE(most, 1.0) << "rt's accumulation restarted";
        } else {
          EXPECT_GT(sum / double(n), 2.0) << "rt's accumulation kept its frames";
        }
      }
      if (std::string(path) == "legacy") {
        const auto t = s.buffer(lighting::kLegacySsao).texels();  // frames in b (0 on the sky)
        double sum = 0.0, most = 0.0;
        size_t n = 0;
        for (size_t i = 2; i < t.size(); i += 4)
          if (t[i] > 0.0f) sum += t[i], most = std::max(most, double(t[i])), ++n;
        ASSERT_GT(n, 0u);
        const double mean = sum / double(n);
        if (row.ssao == restart) {
          EXPECT_LE(most, 1.0) << "SSAO's accumulation restarted";
        } else {
          EXPECT_GT(mean, 2.0) << "SSAO's accumulation kept its frames";
        }
        const double rebuilt = 2.0;  // figure voxelUpdate: 0 kept, 1 patched, 2 rebuilt
        if (row.voxels == restart) {
          EXPECT_EQ(figure("voxelUpdate"), rebuilt);
        } else {
          EXPECT_NE(figure("voxelUpdate"), rebuilt) << "settled voxels are kept (or patched)";
        }
      }
    }
  }
}

}  // namespace
}  // namespace tl::test
