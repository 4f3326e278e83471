// The facade the editor and the command line both use: load a scene, choose a lighting
// path, set the camera and the light, render frames, read any named buffer of the last
// frame, save images. Everything the GUI can do goes through here, so tests drive it too.
#pragma once

#include "albedo/albedo_library.h"
#include "albedo/bake_job.h"
#include "gpu/device.h"
#include "gpu/upload_ring.h"
#include "graph/executor.h"
#include "lighting/common/display_pass.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/lighting_path.h"
#include "scene/environment_map.h"
#include "scene/scene.h"
#include "session/image_io.h"
#include "session/live_compare.h"
#include "session/reference_noise.h"

#include <array>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

// A recoverable error to show the user (bad path name, unavailable path, bad argument).
struct SessionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct View {
  glm::dvec3 position{0.0, 1.0, 5.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  float yfovRadians = 0.9f;  // vertical field of view (perspective)
  float znear = 0.05f;
  // An orthographic view (glTF's orthographic camera): half its height in metres (ymag; the width
  // follows the image's aspect), between the near and the far plane.
  bool orthographic = false;
  float orthoHalfHeight = 1.0f;
  float zfar = 0.0f;  // orthographic only
};

struct Lighting {
  glm::dvec3 sunDirection{-0.4, -1.0, -0.3};  // the direction sunlight travels
  glm::vec3 sunIrradiance{0.0f};  // E on a surface facing the sun (white Lambertian: E/pi)
  glm::vec3 skyRadiance{1.0f};    // uniform radiance L over the whole sphere
  std::optional<float> exposureEv;  // empty: derived from the light (see autoExposureEv)
  float sunAngularRadius = 0.00465f;  // radians (the real sun)
  // The glTF light the sun came from (its name and node), so saving writes it back there.
  std::string sunName;
  std::optional<uint32_t> sunNode;
  // Every light but the sun: point, spot and further directional lights in glTF's units (lux,
  // candela; shaders/shared/lights.h has the scale they are shaded on). Loaded from the scene.
  std::vector<scene::Light> lights;
  // An environment map in place of the uniform sky (shaders/shared/environment.h), turned by
  // environmentRotation (radians, about +Y, counter-clockwise seen from above) and scaled by
  // environmentIntensity. Lighting data like the sun and the sky: set by the CLI's
  // --environment, kept across scene loads. Empty: the uniform sky.
  std::shared_ptr<const scene::EnvironmentMap> environmentMap;
  float environmentRotation = 0.0f;
  float environmentIntensity = 1.0f;
};

// The lighting a scene brings: its sun (as its glTF light, if it came from one), its sky and
// every other light; exposure derived from them. The environment map, its rotation and intensity
// and the sun's angular radius are lighting the scene does not hold: they come from `kept`.
Lighting sceneLighting(const scene::Scene& s, Lighting kept = {});

struct PathInfo {
  std::string name;
  std::string description;
  bool available = true;
  std::string unavailableReason;
  lighting::PathCapabilities capabilities;
  bool plugin = false;  // from plugins/ (lighting::registerLightingPath), not built in
};

class Session {
 public:
  explicit Session(const gpu::DeviceOptions& options = {});
  ~Session();

  gpu::Device& device() { return *device_; }

  // Throws scene::SceneError (one line naming the file) and keeps the previous scene.
  void loadScene(const std::filesystem::path& file, const scene::LoadOptions& options = {});
  // The two halves of loadScene: parsing touches no device and may run on another thread
  // (the editor keeps its UI alive meanwhile); installing uploads to the GPU.
  static std::unique_ptr<scene::Scene> parseScene(const std::filesystem::path& file, const scene::LoadOptions& options = {});
  void installScene(std::unique_ptr<scene::Scene> scene);
  bool hasScene() const { return scene_ != nullptr; }
  const scene::Scene& scene() const;
  // The scene's buffers on the GPU (its draw-call counts: gpu_scene.h).
  const scene::GpuScene& gpuScene() const { return *gpuScene_; }

  // Per-instance hit albedo for the RT path (engine/albedo/): override > baked > texture average. Edits
  // through it show in the next frame.
  albedo::AlbedoLibrary& albedo() { return *albedo_; }
  const albedo::AlbedoLibrary& albedo() const { return *albedo_; }
  // Opens (or creates) the albedo database for this scene and the next ones. Throws
  // albedo::DatabaseError and keeps the database in use before.
  void openAlbedoDatabase(const std::filesystem::path& file, bool create = true);
  std::optional<std::filesystem::path> albedoDatabaseFile() const { return albedoDbFile_; }
  // Closes it: texture averages from now on, for this scene and the next ones (edits not
  // saved are dropped).
  void closeAlbedoDatabase();
  // A bake of this scene into the open database (throws SessionError without one); step it
  // to completion, then albedo().reload().
  std::unique_ptr<albedo::BakeJob> startAlbedoBake(const albedo::BakeOptions& options);
  // The next frame's image becomes what albedo.impact (the change albedo edits made) compares
  // against.
  void captureAlbedoBaseline();
  bool hasAlbedoBaseline() const;

  std::vector<PathInfo> paths() const;
  void setPath(const std::string& name);  // throws SessionError with the reason
  const std::string& path() const { return pathName_; }
  // The path frames render with now, for measurements that ask a path about itself (`bench
  // --rays`: LightingPath::rayFigures).
  const lighting::LightingPath& currentPath() const { return *findPath(pathName_); }
  // The path the others are measured against (PathCapabilities::isReference); empty if none.
  std::string referencePath() const;

  void setView(const View& view);
  const View& view() const { return view_; }
  void useSceneCamera(size_t index);  // throws SessionError when out of range
  void fitViewToScene();

  void setLighting(const Lighting& lighting);
  const Lighting& lighting() const { return lighting_; }
  // The lighting as frames shade it: lighting(), except that a sun found in the environment map
  // (scene::separateEnvironmentSun) is taken out of the map and shaded as the sun, shadows and
  // all, when the artist's own sun is off. environmentSun() is that sun (in the map's frame,
  // before rotation and intensity), empty when none is in use.
  const Lighting& shadedLighting() const { return shaded_; }
  std::optional<scene::EnvironmentSun> environmentSun() const;
  float exposureEv() const;  // the EV in use (explicit or automatic)

  // Animations (morph weights, node translation/rotation/scale): the time (seconds, looping
  // over the scene's animations) the next frame shows; deforming meshes and moving instances
  // take that pose before it renders. The editor advances it while playing; headless renders
  // pick one (--time).
  void setAnimationTime(double seconds) { animationTime_ = seconds; }
  double animationTime() const { return animationTime_; }
  // Seconds each rendered frame advances the animation time afterwards (0: it stays).
  void setAnimationStep(double seconds) { animationStep_ = seconds; }
  double animationStep() const { return animationStep_; }
  bool animated() const { return scene_ && (!scene_->morphAnimations.empty() || !scene_->nodeAnimations.empty()); }
  // Deforming meshes whose vertices the last frame uploaded (0 when none changed).
  size_t meshesDeformedLastFrame() const { return deformedLastFrame_; }
  // Instances the last frame moved (node animation; 0 when none moved).
  size_t instancesMovedLastFrame() const { return movedLastFrame_; }

  void setSize(uint32_t width, uint32_t height);
  lighting::RenderSettings& settings() { return settings_; }
  const lighting::RenderSettings& settings() const { return settings_; }

  // The editor's viewport: adds the display pass (selection outline, any resource shown).
  void setDisplay(std::optional<lighting::DisplayRequest> request) { display_ = std::move(request); }
  // The resource the display was asked to show that the last frame begun does not make (so
  // it showed the final image); empty when it showed what was asked.
  const std::string& displayMissing() const { return displayMissing_; }
  const gpu::Image* displayImage() const { return executor_->image(lighting::kDisplayLdr); }
  // The last finished frame's display.ldr read back (request it), live or of a capture; null
  // when that frame did not read it back.
  const graph::Readback* displayReadback() const;
  VkImageLayout displayImageLayout() const { return executor_->layout(lighting::kDisplayLdr); }
  // The Compare panel: while set, frames render its two sides and the reference in turn (one
  // per frame, each with its own history) and display.ldr shows the compare view instead of
  // the display pass. Throws SessionError naming an unavailable side; nothing changes then.
  void setCompareView(std::optional<CompareView> view);
  const LiveCompare* liveCompare() const { return compare_.get(); }
  LiveCompare* liveCompare() { return compare_.get(); }
  // Instance under pixel (x, y) of the last frame, which must have read back gbuffer.instanceId.
  std::optional<uint32_t> instanceAt(uint32_t x, uint32_t y) const;

  // Read-backs for the last of the next frames: by name, or every resource.
  void requestBuffer(std::string_view name) { requested_.emplace_back(name); }
  void requestAllBuffers() { requestAll_ = true; }

  // Drops every persistent (history) resource: the next frame starts accumulating afresh.
  // Changes of the camera, the light, the scene or a setting need no call: every history
  // decides from the frame key what it keeps (lighting/common/frame_key.h).
  void resetHistory() {
    settle();
    executor_->resetHistory();
  }

  // The frame key of the current state (camera, projection, light, scene, geometry, albedo,
  // every path's history settings) for a frame numbered `frame` of its path.
  lighting::FrameKey frameKey(uint64_t frame = 0) const;
  // What each history did in the last frame (kept, rejected or restarted, and why).
  const std::vector<lighting::HistoryDecision>& historyDecisions() const { return historyLog_; }

  // Renders n frames; the last one reads back the final images and the requested buffers.
  // `afterEach` (optional) is called with the count of frames submitted after each one:
  // progress for long renders (a reference image is many frames). The host records a frame
  // while the GPU runs the one before (framesInFlight()); all are finished on return.
  void renderFrames(uint32_t n, const std::function<void(uint32_t done)>& afterEach = {});
  // How many frames may be in flight at once: 1 waits for each frame before recording the
  // next (the behaviour before frames in flight; a comparison for bench), 2 the default.
  void setFramesInFlight(uint32_t frames);
  uint32_t framesInFlight() const { return framesInFlight_; }
  // One frame in two halves (the editor, whose interface must not wait for the GPU):
  // beginFrame() records and submits a frame with read-backs, without waiting; frameDone()
  // says whether the GPU has finished it; finishFrame() waits if it has not, then collects
  // it (timings, read-backs, the Compare panel's figures). Until then buffer(), timings() and
  // the figures describe the frame before. Changes of the camera, light, settings, path,
  // albedo or display made meanwhile apply to the next frame. Everything that replaces what
  // a frame uses (a scene, a capture, renderFrames, resetHistory) finishes it first.
  // Up to framesInFlight() frames are in flight at once: beginFrame() with that many in
  // flight finishes the oldest first, and finishFrame() finishes the oldest.
  void beginFrame();
  bool frameInFlight() const { return !inFlight_.empty(); }
  uint32_t framesInFlightNow() const { return uint32_t(inFlight_.size()); }
  bool frameDone() const;
  void finishFrame();

  const graph::Readback& buffer(std::string_view name) const;
  // Whether the last frame read back `name` (a path may not produce it).
  bool hasBuffer(std::string_view name) const;
  const std::vector<graph::PhysicalInfo>& resources() const;
  const std::vector<graph::PassTiming>& timings() const;

  // A capture reopened without its scene: while open, frames show its images through
  // the display pass and resources()/buffer()/timings() describe it. Throws SessionError.
  void openCapture(const std::filesystem::path& dir);
  void closeCapture();
  bool hasCapture() const { return capture_ != nullptr; }
  const class CapturedFrame* capture() const { return capture_.get(); }
  // What decoders may know of the scene: the loaded one, or a reopened capture's instance names.
  const scene::Scene* decodingScene() const;
  std::string graphDump() const { return graphDump_; }
  // The last rendered frame's graph as Graphviz DOT (graph::RenderGraph::dot).
  const std::string& graphDot() const { return graphDot_; }
  // Writes the graph to `file`: DOT for a .dot or .gv file, else the text dump. Atomic;
  // throws SessionError naming the file when it cannot be written.
  void writeGraph(const std::filesystem::path& file) const;
  // GPU milliseconds of each frame of the last renderFrames call, and per pass (in order).
  const std::vector<double>& frameGpuMs() const { return frameGpuMs_; }
  const std::vector<std::pair<std::string, std::vector<double>>>& passGpuMs() const { return passGpuMs_; }
  // The loaded scene's size, which automatic settings derive from (render_settings.h).
  lighting::SceneSize sceneSize() const;
  uint64_t frameIndex() const { return frameIndex_; }
  // The active path's figures about the last frame (see LightingPath::figures).
  std::vector<std::pair<std::string, double>> pathFigures() const { return path_->figures(); }
  // The reference's noise at the last finished frame (session/reference_noise.h): empty when
  // that frame was not the reference's or some pixel has fewer than 2 samples.
  std::optional<ReferenceNoise> referenceNoise() const;
  // Switches to the reference path and renders it, on from what it has accumulated, until the
  // relative standard error of its image is at most target.relativeStdError or a pixel has
  // target.maxSamples samples; `beforeFrame` runs before each frame (progress, read-back
  // requests: the last frame reads back as renderFrames' does). Throws SessionError when this
  // build has no reference path or the target is not a number > 0.
  ReferenceConvergence renderReferenceUntilNoise(const NoiseTarget& target,
                                                 const std::function<void(const ReferenceConvergence&)>& beforeFrame = {});
  // Pins the next frame's index (it seeds per-frame noise): reproducible frames for tests.
  void setFrameIndex(uint64_t index) { frameIndex_ = index; }

  // .exr: scene-linear radiance before exposure (composite.hdr), in half floats when every
  // value fits them and in 32-bit floats when some do not (the report says how many);
  // .png: the tonemapped display image (tonemap.ldr). Written atomically.
  ImageWriteReport saveImage(const std::filesystem::path& file) const;

  uint32_t validationErrors() const { return device_->validationErrorCount(); }

 private:
  void buildFrameConstants(shared::FrameConstants& fc, uint32_t frameNumber, bool jitter) const;
  void beginOne(bool readback);
  void finishOne();
  void settle();  // finishes a frame in flight
  // What finishing a submitted frame needs to know about it.
  struct InFlight {
    lighting::LightingPath* path = nullptr;
    std::string compared;         // the compare view's side it renders ("" outside a compare)
    uint64_t compareGeneration = 0;
    lighting::FrameKey key;
    float exposure = 1.0f;
    std::string noise;  // the compared reference's noise estimate, read back for the Compare panel ("": none)
    // What the frame's path said when it was built (a later frame may be built before this one
    // is finished): the reference's sample count and the accumulation's history decision.
    uint32_t referenceSamples = 0;
    std::optional<lighting::HistoryDecision> accumulation;
  };
  std::deque<InFlight> inFlight_;  // oldest first
  uint32_t framesInFlight_ = gpu::kMaxFramesInFlight;
  uint64_t compareGeneration_ = 0;  // counts compare views, so a frame finds the one it was for

  std::unique_ptr<gpu::Device> device_;
  std::unique_ptr<scene::Scene> scene_;
  std::unique_ptr<scene::GpuScene> gpuScene_;
  std::unique_ptr<albedo::AlbedoLibrary> albedo_;
  std::unique_ptr<class CapturedFrame> capture_;
  std::unique_ptr<lighting::DisplayPass> captureDisplay_;
  std::optional<std::filesystem::path> albedoDbFile_;
  std::unique_ptr<graph::Executor> executor_;
  std::vector<std::unique_ptr<lighting::LightingPath>> paths_;
  lighting::LightingPath* path_ = nullptr;
  std::string pathName_;
  std::unique_ptr<class FramePipeline> pipeline_;  // the frame's buffers and pass order (session/frame_pipeline.h)
  // The environment map's SH projection, recomputed when the map, its rotation or its
  // intensity change (setLighting).
  std::array<glm::vec4, 9> environmentSh_{};
  lighting::RenderSettings settings_;
  lighting::RenderSettings frameSettings_;  // settings_ with automatic values resolved: what the frame renders with
  View view_;
  std::optional<View> previousView_;
  Lighting lighting_;
  Lighting shaded_;  // shadedLighting()
  std::shared_ptr<const scene::EnvironmentMap> separatedFrom_;  // the map environmentSun_ was looked for in
  std::optional<scene::SunAndSky> separatedSun_;
  void updateShadedLighting();
  std::optional<lighting::DisplayRequest> display_;
  std::string displayMissing_;
  std::unique_ptr<LiveCompare> compare_;
  std::map<std::string, View> comparePrevious_;  // each compared path's own previous view
  std::map<std::string, uint64_t> compareFrames_;  // and its own frame count (noise, checkerboards)
  std::vector<lighting::HistoryDecision> historyLog_;
  lighting::LightingPath* findPath(const std::string& name) const;
  std::vector<std::string> requested_;
  bool requestAll_ = false;
  std::string graphDump_, graphDot_;
  std::vector<double> frameGpuMs_;
  std::vector<std::pair<std::string, std::vector<double>>> passGpuMs_;
  uint64_t frameIndex_ = 0;
  double animationTime_ = 0.0, animationStep_ = 0.0;
  std::vector<std::vector<float>> appliedWeights_;  // per mesh: the pose its vertices hold
  std::vector<std::vector<glm::mat4>> appliedJoints_;  // per skinned mesh: the joint matrices its vertices hold
  size_t deformedLastFrame_ = 0, movedLastFrame_ = 0;
  void applyDeformation(const std::vector<glm::dmat4>& nodeWorld);
  float brightestEmission_ = 0.0f;  // luminance of the scene's brightest emissive material
};

// Exposure that maps a white surface lit by this sun and sky to about 1.0 before tonemapping.
// In scenes lit by emitters, a white surface near the brightest one (taken as a tenth of its
// radiance: a rule of thumb for a light of modest solid angle) counts too, and so does a white
// surface facing the brightest other light (a point or spot light from 2 m).
// sceneScale: the scene's extent (bounds diagonal); lights are taken as seen from a fifth of it.
float autoExposureEv(const Lighting& lighting, float brightestEmission = 0.0f, float sceneScale = 10.0f);

}  // namespace tl::session
