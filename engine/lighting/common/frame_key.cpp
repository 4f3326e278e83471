#include "lighting/common/frame_key.h"

#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace tl::lighting {

const char* partName(FramePart p) {
  switch (p) {
    case FramePart::CameraPosition: return "camera.position";
    case FramePart::CameraOrientation: return "camera.orientation";
    case FramePart::Projection: return "projection";
    case FramePart::Sun: return "sun";
    case FramePart::Sky: return "sky";
    case FramePart::Scene: return "scene";
    case FramePart::Geometry: return "geometry";
    case FramePart::Albedo: return "albedo";
    case FramePart::Settings: return "settings";
    case FramePart::CameraCut: return "camera.cut";
    case FramePart::FrameGap: return "frame.gap";
    case FramePart::Count: break;
  }
  return "?";
}

std::string describeParts(FrameParts mask) {
  std::string out;
  for (uint32_t i = 0; i < uint32_t(FramePart::Count); ++i)
    if (mask & (1u << i)) out += (out.empty() ? "" : ", ") + std::string(partName(FramePart(i)));
  return out.empty() ? "nothing" : out;
}

const char* actionName(HistoryAction a) {
  switch (a) {
    case HistoryAction::Keep: return "keep";
    case HistoryAction::Reject: return "reject";
    case HistoryAction::Restart: return "restart";
  }
  return "?";
}

uint64_t FrameKey::settingsOf(std::string_view path) const {
  auto it = settings.find(path);
  return it != settings.end() ? it->second : 0;
}

uint64_t KeyHasher::done() const { return scene::hashBytes(values_.data(), values_.size() * sizeof(double)); }

bool cameraJumped(const glm::dvec3& fromPosition, const glm::dvec3& fromForward, const glm::dvec3& toPosition,
                  const glm::dvec3& toForward, double sceneScale) {
  const double moved = glm::length(toPosition - fromPosition);
  const double turned = glm::dot(glm::normalize(fromForward), glm::normalize(toForward));
  return moved > 0.2 * std::max(sceneScale, 1e-6) || turned < 0.5;
}

FrameParts differingParts(const FrameKey& a, const FrameKey& b) {
  FrameParts changed = 0;
  for (uint32_t i = 0; i < kHashedPartCount; ++i)
    if (a.hashes[i] != b.hashes[i]) changed |= 1u << i;
  return changed;
}

FrameParts changedParts(const FrameKey& before, const FrameKey& now, std::string_view path) {
  FrameParts changed = differingParts(before, now);
  if (before.settingsOf(path) != now.settingsOf(path)) changed |= partBit(FramePart::Settings);
  // Frame numbers restart with a compare or a pinned frame index: anything but the next one is a gap.
  const bool gap = now.frame != before.frame + 1;
  if (gap) changed |= partBit(FramePart::FrameGap);
  // Reprojection follows the camera from the previous frame only: over a gap, any camera
  // change is a cut for the histories that reproject.
  if (cameraJumped(before.cameraPosition, before.cameraForward, now.cameraPosition, now.cameraForward, now.sceneScale) ||
      (gap && (changed & kCameraParts)))
    changed |= partBit(FramePart::CameraCut);
  return changed;
}

HistoryDecision HistoryKeeper::advance(const HistoryPolicy& policy, const FrameKey& key, std::string_view path,
                                       std::vector<HistoryDecision>* log, HistoryFound found) {
  HistoryDecision d;
  d.history = policy.history;
  d.path = std::string(path);
  d.changed = last_ ? changedParts(*last_, key, path) : kAllParts;
  const FrameParts restart = d.changed & (policy.restartOn | found.restarts);
  const FrameParts reject = d.changed & policy.rejectOn;
  if (!last_) d.action = HistoryAction::Restart;  // nothing to keep yet
  else if (restart || !found.stored) d.acted = restart, d.action = HistoryAction::Restart;
  else if (reject) d.acted = reject, d.action = HistoryAction::Reject;
  last_ = key;
  if (log) log->push_back(d);
  return d;
}

}  // namespace tl::lighting
