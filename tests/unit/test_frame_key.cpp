// The frame key's comparison rules without a GPU: which parts differ, when a camera move is a
// cut, when frames were skipped, per-path settings, and how a history's policy turns changed
// parts into keep / reject / restart.
#include "lighting/common/frame_key.h"

#include <gtest/gtest.h>

namespace tl::lighting {
namespace {

FrameKey baseKey() {
  FrameKey k;
  for (uint32_t i = 0; i < kHashedPartCount; ++i) k.hashes[i] = 100 + i;
  k.settings = {{"rt", 7}, {"legacy", 8}};
  k.cameraPosition = {1.0, 2.0, 3.0};
  k.cameraForward = {0.0, 0.0, -1.0};
  k.sceneScale = 10.0;
  k.frame = 41;
  return k;
}

FrameKey next(FrameKey k) {
  ++k.frame;
  return k;
}

TEST(FrameKey, TheNextFrameOfAStillSceneChangesNothing) {
  const FrameKey a = baseKey();
  EXPECT_EQ(changedParts(a, next(a), "rt"), 0u);
  EXPECT_EQ(describeParts(0), "nothing");
}

TEST(FrameKey, EachHashedPartIsReportedByName) {
  for (uint32_t i = 0; i < kHashedPartCount; ++i) {
    const FrameKey a = baseKey();
    FrameKey b = next(a);
    ++b.hashes[i];
    EXPECT_EQ(changedParts(a, b, "rt"), 1u << i) << partName(FramePart(i));
    EXPECT_EQ(differingParts(a, b), 1u << i);
  }
}

TEST(FrameKey, SettingsArePerPath) {
  const FrameKey a = baseKey();
  FrameKey b = next(a);
  b.settings["rt"] = 9;
  EXPECT_EQ(changedParts(a, b, "rt"), partBit(FramePart::Settings));
  EXPECT_EQ(changedParts(a, b, "legacy"), 0u);
  EXPECT_EQ(changedParts(a, b, "reference"), 0u) << "a path without history settings hears none";
  EXPECT_EQ(differingParts(a, b), 0u) << "settings are not a hashed part";
}

TEST(FrameKey, AJumpOrASharpTurnIsACutAndASmallStepIsNot) {
  const FrameKey a = baseKey();
  FrameKey step = next(a), jump = next(a), turn = next(a), glance = next(a);
  step.cameraPosition.x += 1.9;  // under a fifth of the 10 m scene
  step.hash(FramePart::CameraPosition) += 1;
  jump.cameraPosition.x += 2.1;
  jump.hash(FramePart::CameraPosition) += 1;
  turn.cameraForward = glm::normalize(glm::dvec3(0.9, 0.0, -0.4));  // about 66 degrees
  turn.hash(FramePart::CameraOrientation) += 1;
  glance.cameraForward = glm::normalize(glm::dvec3(0.5, 0.0, -1.0));  // about 27 degrees
  glance.hash(FramePart::CameraOrientation) += 1;
  EXPECT_EQ(changedParts(a, step, "rt"), partBit(FramePart::CameraPosition));
  EXPECT_EQ(changedParts(a, jump, "rt"), parts(FramePart::CameraPosition, FramePart::CameraCut));
  EXPECT_EQ(changedParts(a, turn, "rt"), parts(FramePart::CameraOrientation, FramePart::CameraCut));
  EXPECT_EQ(changedParts(a, glance, "rt"), partBit(FramePart::CameraOrientation));
  EXPECT_TRUE(cameraJumped(a.cameraPosition, a.cameraForward, jump.cameraPosition, jump.cameraForward, a.sceneScale));
  EXPECT_FALSE(cameraJumped(a.cameraPosition, a.cameraForward, step.cameraPosition, step.cameraForward, a.sceneScale));
}

TEST(FrameKey, SkippedFramesAreAGapAndCameraMotionOverThemACut) {
  const FrameKey a = baseKey();
  FrameKey later = a, movedLater = a, zoomedLater = a;
  later.frame = movedLater.frame = zoomedLater.frame = a.frame + 3;
  movedLater.cameraPosition.x += 0.01;
  movedLater.hash(FramePart::CameraPosition) += 1;
  zoomedLater.hash(FramePart::Projection) += 1;
  EXPECT_EQ(changedParts(a, later, "rt"), partBit(FramePart::FrameGap));
  EXPECT_EQ(changedParts(a, movedLater, "rt"), parts(FramePart::CameraPosition, FramePart::FrameGap, FramePart::CameraCut));
  EXPECT_EQ(changedParts(a, zoomedLater, "rt"), parts(FramePart::Projection, FramePart::FrameGap, FramePart::CameraCut));
  FrameKey again = a;  // the same frame number again (a pinned frame index) is a gap too
  EXPECT_EQ(changedParts(a, again, "rt"), partBit(FramePart::FrameGap));
}

TEST(HistoryKeeper, DecidesFromItsPolicyAndLogs) {
  const HistoryPolicy policy{"test.history", parts(FramePart::Scene, FramePart::CameraCut), parts(FramePart::Sun)};
  HistoryKeeper keeper;
  std::vector<HistoryDecision> log;
  FrameKey k = baseKey();
  HistoryDecision d = keeper.advance(policy, k, "rt", &log);
  EXPECT_EQ(d.action, HistoryAction::Restart) << "the first frame has nothing to keep";
  EXPECT_EQ(d.acted, 0u);
  EXPECT_EQ(d.changed, kAllParts);

  k = next(k);
  k.hash(FramePart::Albedo) += 1;  // not in the policy
  d = keeper.advance(policy, k, "rt", &log);
  EXPECT_EQ(d.action, HistoryAction::Keep);
  EXPECT_EQ(d.changed, partBit(FramePart::Albedo));
  EXPECT_EQ(d.acted, 0u);

  k = next(k);
  k.hash(FramePart::Sun) += 1;
  d = keeper.advance(policy, k, "rt", &log);
  EXPECT_EQ(d.action, HistoryAction::Reject);
  EXPECT_EQ(d.acted, partBit(FramePart::Sun));

  k = next(k);
  k.hash(FramePart::Sun) += 1;
  k.hash(FramePart::Scene) += 1;
  d = keeper.advance(policy, k, "rt", &log);
  EXPECT_EQ(d.action, HistoryAction::Restart) << "a restart wins over a rejection";
  EXPECT_EQ(d.acted, partBit(FramePart::Scene));

  k = next(k);
  d = keeper.advance(policy, k, "rt", &log, {false});
  EXPECT_EQ(d.action, HistoryAction::Restart) << "history the executor no longer holds is gone";
  EXPECT_EQ(d.acted, 0u);

  k = next(k);
  k.hash(FramePart::CameraPosition) += 1;
  d = keeper.advance(policy, k, "rt", &log, {true, partBit(FramePart::CameraPosition)});
  EXPECT_EQ(d.action, HistoryAction::Restart) << "a part the history judged itself";
  EXPECT_EQ(d.acted, partBit(FramePart::CameraPosition));

  k = next(k);
  d = keeper.advance(policy, k, "rt", &log, {true, partBit(FramePart::CameraPosition)});
  EXPECT_EQ(d.action, HistoryAction::Keep) << "only when that part changed";

  ASSERT_EQ(log.size(), 7u);
  EXPECT_EQ(log[2].history, "test.history");
  EXPECT_EQ(log[2].path, "rt");
  EXPECT_EQ(std::string(actionName(log[2].action)), "reject");
}

}  // namespace
}  // namespace tl::lighting
