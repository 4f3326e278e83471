// One frame key for every history. The session describes each frame in named parts
// (camera, projection, light, scene, geometry, albedo, each path's settings); every history
// keeps the key of the last frame it saw and decides from the parts that changed whether it
// keeps, rejects or restarts what it accumulated. No history hashes its own inputs, so a
// value that changes the image cannot be left out of one key and not another.
// docs/design/frame-key.md lists who listens to which part.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tl::lighting {

enum class FramePart : uint32_t {
  // Hashed from the session's state:
  CameraPosition,     // the camera's world position
  CameraOrientation,  // its forward and up directions
  Projection,         // vertical field of view, near plane, image size (not TAA's jitter)
  Sun,                // the light: sun direction, irradiance, angular radius, and every other light
  Sky,                // the light: uniform sky radiance
  Scene,              // the environment: which scene is loaded (a new upload: another file, a reload)
  Geometry,           // deforming meshes' vertex versions (animation) and instance transforms
  Albedo,             // per-instance hit albedo (overrides, the baked database)
  Settings,           // the settings the listening path's history depends on (LightingPath::historySettings)
  // Derived when two keys are compared:
  CameraCut,  // motion no history can reproject: the camera jumped (more than a fifth of the
              // scene) or turned (more than 60 degrees), or moved over frames the history skipped
  FrameGap,   // the history skipped frames of its path (it did not run in the previous one)
  Count
};
inline constexpr uint32_t kHashedPartCount = uint32_t(FramePart::Settings);  // Settings is per path

using FrameParts = uint32_t;  // one bit per FramePart
constexpr FrameParts partBit(FramePart p) { return 1u << uint32_t(p); }
template <class... P>
constexpr FrameParts parts(P... p) { return (partBit(p) | ...); }
inline constexpr FrameParts kAllParts = (1u << uint32_t(FramePart::Count)) - 1u;
inline constexpr FrameParts kCameraParts = parts(FramePart::CameraPosition, FramePart::CameraOrientation, FramePart::Projection);

// "camera.position", "sun", ...: the names the report, the editor and the tests use.
const char* partName(FramePart p);
// Comma-separated names of the parts in `mask` ("nothing" for none).
std::string describeParts(FrameParts mask);

struct FrameKey {
  std::array<uint64_t, kHashedPartCount> hashes{};
  // Per lighting path: a hash of the settings its history depends on.
  std::map<std::string, uint64_t, std::less<>> settings;
  // The values behind the camera parts and the scene's size: a cut is a matter of distance.
  glm::dvec3 cameraPosition{0.0};
  glm::dvec3 cameraForward{0.0, 0.0, -1.0};
  double sceneScale = 1.0;  // the scene's diagonal (m)
  uint64_t frame = 0;       // the frame number of the path it renders (each path counts its own in a compare)

  uint64_t hash(FramePart p) const { return hashes[uint32_t(p)]; }
  uint64_t& hash(FramePart p) { return hashes[uint32_t(p)]; }
  uint64_t settingsOf(std::string_view path) const;  // 0 for a path without history settings
};

// The camera moved further than a history can follow: more than a fifth of the scene, or a
// turn of more than 60 degrees (the session's camera cut, session/view_math.h, is the same).
bool cameraJumped(const glm::dvec3& fromPosition, const glm::dvec3& fromForward, const glm::dvec3& toPosition,
                  const glm::dvec3& toForward, double sceneScale);

// The hashed parts (not Settings, not the derived ones) that differ between two keys.
FrameParts differingParts(const FrameKey& a, const FrameKey& b);
// The parts that differ from `before` to `now` for the history of `path`, derived ones included.
FrameParts changedParts(const FrameKey& before, const FrameKey& now, std::string_view path);

// Hashes of values for the key's parts (xxHash64 of their bytes, in order).
class KeyHasher {
 public:
  KeyHasher& add(double v) { values_.push_back(v); return *this; }
  KeyHasher& add(const glm::dvec3& v) { return add(v.x).add(v.y).add(v.z); }
  KeyHasher& add(const glm::vec3& v) { return add(double(v.x)).add(double(v.y)).add(double(v.z)); }
  template <class... T>
  KeyHasher& all(const T&... v) { (add(v), ...); return *this; }
  uint64_t done() const;
 private:
  std::vector<double> values_;
};

// What one history did with one frame, for the tests, the editor and the inspector.
enum class HistoryAction {
  Keep,     // kept (reprojected, or patched where only some of it changed)
  Reject,   // kept, but clipped to what this frame's samples allow (the light changed)
  Restart,  // dropped: accumulation starts over from this frame
};
const char* actionName(HistoryAction a);

struct HistoryDecision {
  std::string history;  // "reference.accumulation", "rt.temporal", "legacy.voxels", "legacy.ssao", "taa"
  std::string path;     // the lighting path whose frame it was
  FrameParts changed = 0;  // every part that changed since the frame this history last saw
  FrameParts acted = 0;    // those that decided the action; none for a restart with nothing
                           // to keep (the first frame, history lost to a resize or a reset)
  HistoryAction action = HistoryAction::Keep;
};

// Which parts restart a history and which make it reject; the rest it keeps across.
struct HistoryPolicy {
  const char* history;
  FrameParts restartOn = 0;
  FrameParts rejectOn = 0;
};

// What a history found itself: whether its resources still hold the last frame's contents
// (false after a resize or Session::resetHistory), and parts it judged to restart it when they
// changed (the voxels: a camera move that shifted their placement in the world).
struct HistoryFound {
  bool stored = true;
  FrameParts restarts = 0;
};

// One history's memory of the key: the key of the last frame it ran in.
class HistoryKeeper {
 public:
  // Decides this frame's action from the parts changed since the last frame it saw (every
  // part the first time) and remembers the key; `log` (may be null) receives the decision.
  HistoryDecision advance(const HistoryPolicy& policy, const FrameKey& key, std::string_view path,
                          std::vector<HistoryDecision>* log, HistoryFound found = {});
  void forget() { last_.reset(); }

 private:
  std::optional<FrameKey> last_;
};

}  // namespace tl::lighting
