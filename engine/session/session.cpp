#include "session/session.h"

#include "lighting/common/albedo_view_pass.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/taa_pass.h"
#include "scene/morph.h"
#include "scene/node_animation.h"
#include "scene/skinning.h"
#include "session/captured_frame.h"
#include "session/frame_pipeline.h"
#include "session/image_io.h"
#include "session/view_math.h"
#include "shared/taa.h"

#include <fmt/format.h>

#include <cstring>

#include <spdlog/spdlog.h>

namespace tl::session {

Session::Session(const gpu::DeviceOptions& options)
    : device_(std::make_unique<gpu::Device>(options)),
      executor_(std::make_unique<graph::Executor>(*device_)),
      pipeline_(std::make_unique<FramePipeline>(*device_)) {
  for (lighting::LightingPathFactory make : lighting::lightingPathRegistry()) paths_.push_back(make());
  path_ = paths_.front().get();
  pathName_ = path_->name();
}

Session::~Session() {
  if (device_) device_->waitIdle();
}

void Session::settle() {
  while (!inFlight_.empty()) finishOne();
}

const scene::Scene& Session::scene() const {
  if (!scene_) throw SessionError("no scene is loaded");
  return *scene_;
}

std::unique_ptr<scene::Scene> Session::parseScene(const std::filesystem::path& file, const scene::LoadOptions& options) {
  auto loaded = std::make_unique<scene::Scene>(scene::loadGltf(file, options));
  if (loaded->instances.empty()) throw scene::SceneError(fmt::format("{}: the scene has no meshes to draw", file.string()));
  return loaded;
}

void Session::loadScene(const std::filesystem::path& file, const scene::LoadOptions& options) {
  installScene(parseScene(file, options));
}

void Session::installScene(std::unique_ptr<scene::Scene> loaded) {
  settle();
  for (auto& w : loaded->warnings) spdlog::warn("{}", w);
  device_->waitIdle();
  // The executor forgets the old scene's buffers and any capture's images before they go.
  executor_->unbindImported();
  capture_.reset();  // a scene replaces a reopened capture
  gpuScene_ = std::make_unique<scene::GpuScene>(*device_, *loaded);
  scene_ = std::move(loaded);
  albedo_ = std::make_unique<albedo::AlbedoLibrary>(*scene_);
  if (albedoDbFile_) {
    try {
      albedo_->attach(std::make_unique<albedo::AlbedoDatabase>(*albedoDbFile_));
    } catch (const albedo::DatabaseError& e) {
      spdlog::warn("{} (texture averages are used)", e.what());
    }
  }
  // Pipelines depend on the scene's descriptor layout: rebuild them with the new scene.
  pipeline_->resetPasses();
  executor_->resetHistory();
  previousView_.reset();
  comparePrevious_.clear();
  if (compare_)
    compare_ = std::make_unique<LiveCompare>(compare_->view(), compare_->referencePath(), compare_->referenceUnavailable());
  animationTime_ = 0.0;
  // The upload holds every mesh at rest (all weights 0).
  appliedWeights_.assign(scene_->meshes.size(), {});
  appliedJoints_.assign(scene_->meshes.size(), {});  // the upload holds skinned meshes in their bind pose
  for (size_t m = 0; m < scene_->meshes.size(); ++m) appliedWeights_[m].assign(scene_->meshes[m].morphTargets.size(), 0.0f);

  lighting_ = sceneLighting(*scene_, std::move(lighting_));
  updateShadedLighting();
  brightestEmission_ = 0.0f;
  for (const auto& m : scene_->materials)
    brightestEmission_ = std::max(brightestEmission_, shared::tlLuminance(m.emissiveFactor * m.emissiveStrength));
  if (!scene_->cameras.empty()) useSceneCamera(0);
  else fitViewToScene();
}

Lighting sceneLighting(const scene::Scene& s, Lighting kept) {
  const scene::Environment& env = s.environment;
  Lighting l = std::move(kept);
  l.sunDirection = env.sunDirection;
  l.sunIrradiance = env.sunFromFile ? env.sunIrradiance : glm::vec3(0.0f);
  l.skyRadiance = env.skyRadiance;
  l.sunName = env.sunLight ? s.lights[*env.sunLight].name : std::string();
  l.sunNode = env.sunLight ? s.lights[*env.sunLight].node : std::nullopt;
  l.lights.clear();
  for (size_t i = 0; i < s.lights.size(); ++i)
    if (i != env.sunLight) l.lights.push_back(s.lights[i]);
  l.exposureEv.reset();
  return l;
}

void Session::openAlbedoDatabase(const std::filesystem::path& file, bool create) {
  if (!albedo_) throw SessionError("load a scene before opening an albedo database");
  albedo_->attach(std::make_unique<albedo::AlbedoDatabase>(file, create));
  albedoDbFile_ = file;
}

void Session::closeAlbedoDatabase() {
  albedoDbFile_.reset();
  if (albedo_) albedo_->attach(nullptr);
}

void Session::captureAlbedoBaseline() { pipeline_->albedoView().captureBaseline(); }
bool Session::hasAlbedoBaseline() const { return pipeline_->albedoView().hasBaseline(); }

std::unique_ptr<albedo::BakeJob> Session::startAlbedoBake(const albedo::BakeOptions& options) {
  if (!albedo_ || !albedo_->database()) throw SessionError("open an albedo database before baking");
  return std::make_unique<albedo::BakeJob>(*device_, *scene_, *gpuScene_, *albedo_->database(), options);
}

std::vector<PathInfo> Session::paths() const {
  std::vector<PathInfo> out;
  for (auto& p : paths_) {
    auto reason = p->unavailableReason(*device_);
    out.push_back({p->name(), p->description(), !reason, reason.value_or(""), p->capabilities(),
                   lighting::isPluginPath(p->name())});
  }
  return out;
}

void Session::setPath(const std::string& name) {
  for (auto& p : paths_) {
    if (p->name() != name) continue;
    if (auto reason = p->unavailableReason(*device_))
      throw SessionError(fmt::format("lighting path `{}` is unavailable on {}: {}", name, device_->name(), *reason));
    path_ = p.get();
    pathName_ = name;
    return;
  }
  std::string known;
  for (auto& p : paths_) known += (known.empty() ? "" : ", ") + p->name();
  throw SessionError(fmt::format("unknown lighting path `{}` (available: {})", name, known));
}

std::string Session::referencePath() const {
  for (auto& p : paths_)
    if (p->capabilities().isReference) return p->name();
  return {};
}

lighting::LightingPath* Session::findPath(const std::string& name) const {
  for (auto& p : paths_)
    if (p->name() == name) return p.get();
  return nullptr;
}

void Session::setCompareView(std::optional<CompareView> view) {
  if (!view) {
    if (compare_) ++compareGeneration_;
    compare_.reset();
    comparePrevious_.clear();
    compareFrames_.clear();
    return;
  }
  for (const std::string& side : {view->left, view->right}) {
    lighting::LightingPath* p = findPath(side);
    if (!p) throw SessionError(fmt::format("cannot compare `{}`: no such lighting path", side));
    if (auto reason = p->unavailableReason(*device_))
      throw SessionError(fmt::format("cannot compare `{}`: {}", side, *reason));
  }
  if (compare_) {
    compare_->setView(*view);
    return;
  }
  ++compareGeneration_;
  const lighting::LightingPath* reference = findPath(referencePath());
  compare_ = std::make_unique<LiveCompare>(*view, reference ? reference->name() : std::string(),
                                           reference ? reference->unavailableReason(*device_)
                                                     : std::optional<std::string>("this build has no reference path"));
}

namespace {
// Every light but the sun joins the frame key's light part.
lighting::KeyHasher& addLights(lighting::KeyHasher& h, const std::vector<scene::Light>& lights) {
  for (const auto& l : lights)
    h.all(double(l.type), l.color, double(l.intensity), double(l.range.value_or(0.0f)), double(l.innerConeAngle),
          double(l.outerConeAngle), l.position, l.direction, double(l.width), double(l.height), double(l.radius),
          double(l.length), double(l.twoSided), l.widthAxis, double(l.hidden));
  return h;
}
}  // namespace

lighting::FrameKey Session::frameKey(uint64_t frame) const {
  using lighting::FramePart;
  using lighting::KeyHasher;
  lighting::FrameKey key;
  key.hash(FramePart::CameraPosition) = KeyHasher().add(view_.position).done();
  key.hash(FramePart::CameraOrientation) = KeyHasher().all(view_.forward, view_.up).done();
  key.hash(FramePart::Projection) =
      KeyHasher()
          .all(double(view_.yfovRadians), double(view_.znear), double(settings_.width), double(settings_.height),
               double(view_.orthographic), double(view_.orthoHalfHeight), double(view_.zfar))
          .done();
  KeyHasher light;
  light.all(glm::normalize(shaded_.sunDirection), shaded_.sunIrradiance, double(shaded_.sunAngularRadius));
  key.hash(FramePart::Sun) = addLights(light, shaded_.lights).done();
  KeyHasher sky;
  sky.add(shaded_.skyRadiance);
  if (const auto& map = shaded_.environmentMap)
    sky.all(double(map->contentHash >> 32), double(map->contentHash & 0xFFFFFFFFu), double(shaded_.environmentRotation),
            double(shaded_.environmentIntensity));
  key.hash(FramePart::Sky) = sky.done();
  key.hash(FramePart::Scene) = gpuScene_ ? gpuScene_->id() : 0;
  if (scene_) {
    std::vector<glm::dmat4> transforms;
    transforms.reserve(scene_->instances.size());
    for (const auto& instance : scene_->instances) transforms.push_back(instance.transform);
    const uint64_t geometry[] = {gpuScene_ ? gpuScene_->geometryVersion() : 0,
                                 scene::hashBytes(transforms.data(), transforms.size() * sizeof(glm::dmat4))};
    key.hash(FramePart::Geometry) = scene::hashBytes(geometry, sizeof geometry);
    key.sceneScale = scene_->bounds.valid() ? glm::length(scene_->bounds.size()) : 1.0;
  }
  key.hash(FramePart::Albedo) = albedo_ ? albedo_->version() : 0;
  for (const auto& p : paths_) key.settings[p->name()] = lighting::historySettingsHash(settings_, p->name());
  key.cameraPosition = view_.position;
  key.cameraForward = view_.forward;
  key.frame = frame;
  return key;
}

void Session::setView(const View& view) {
  View v = view;
  double len = glm::length(v.forward);
  if (!(len > 1e-12) || !std::isfinite(len)) throw SessionError("the view direction is zero or not finite");
  v.forward /= len;
  if (!(v.yfovRadians > 0.0f && v.yfovRadians < 3.1f)) throw SessionError("the field of view must be between 0 and 178 degrees");
  if (v.orthographic && !(v.orthoHalfHeight > 0.0f && std::isfinite(v.orthoHalfHeight) && v.znear >= 0.0f &&
                          std::isfinite(v.zfar) && v.zfar > v.znear))
    throw SessionError("an orthographic view needs a positive, finite height and 0 <= near < far");
  if (glm::length(glm::cross(v.forward, v.up)) < 1e-6) v.up = std::abs(v.forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  view_ = v;
}

void Session::useSceneCamera(size_t index) {
  const auto& cams = scene().cameras;
  if (index >= cams.size())
    throw SessionError(fmt::format("scene {} has {} camera(s); camera {} does not exist", scene_->name, cams.size(), index));
  const auto& c = cams[index];
  View v;
  v.position = c.position;
  v.forward = c.orientation * glm::dvec3(0.0, 0.0, -1.0);
  v.up = c.orientation * glm::dvec3(0.0, 1.0, 0.0);
  v.yfovRadians = c.yfovRadians;
  // The importer holds znear > 0 (and zfar > znear for an orthographic camera); the floor
  // only keeps depth precision in a scene a million times the near plane.
  const float diagonal = sceneSize().diagonal;
  v.znear = std::max(c.znear, 1e-7f * diagonal);
  if (c.orthographic) {
    v.orthographic = true;
    v.orthoHalfHeight = c.ymag;
    v.znear = std::max(0.0f, c.znear);
    v.zfar = c.zfar.value_or(v.znear + 2.0f * diagonal + float(glm::length(c.position - scene_->bounds.center())));
  }
  setView(v);
}

void Session::fitViewToScene() {
  const auto& b = scene().bounds;
  glm::dvec3 c = b.valid() ? b.center() : glm::dvec3(0.0);
  double r = b.valid() ? 0.5 * glm::length(b.size()) : 1.0;
  View v;
  v.forward = glm::normalize(glm::dvec3(-0.4, -0.35, -1.0));
  v.position = c - v.forward * (r / std::tan(0.45) + r);
  v.znear = float(std::max(1e-30, r * 1e-3));
  setView(v);
}

void Session::setSize(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0 || width > 16384 || height > 16384)
    throw SessionError(fmt::format("image size {}x{} is out of range (1..16384)", width, height));
  settings_.width = width;
  settings_.height = height;
}

void Session::setLighting(const Lighting& lighting) {
  lighting_ = lighting;
  updateShadedLighting();
}

void Session::updateShadedLighting() {
  const auto& map = lighting_.environmentMap;
  if (map != separatedFrom_) {
    separatedSun_ = map ? scene::separateEnvironmentSun(*map) : std::nullopt;
    separatedFrom_ = map;
  }
  const Lighting before = std::move(shaded_);
  shaded_ = lighting_;
  const glm::vec3& artistSun = lighting_.sunIrradiance;
  if (separatedSun_ && !(std::max({artistSun.r, artistSun.g, artistSun.b}) > 0.0f)) {
    const scene::EnvironmentSun& sun = separatedSun_->sun;
    const glm::vec2 cs(std::cos(lighting_.environmentRotation), std::sin(lighting_.environmentRotation));
    shaded_.sunDirection = -glm::dvec3(shared::tlEnvMapToWorld(glm::vec3(sun.direction), cs));
    shaded_.sunIrradiance = sun.irradiance * lighting_.environmentIntensity;
    shaded_.sunAngularRadius = float(sun.angularRadius);
    shaded_.environmentMap = separatedSun_->sky;
  }
  const bool shChanged = shaded_.environmentMap &&
                         (shaded_.environmentMap != before.environmentMap ||
                          shaded_.environmentRotation != before.environmentRotation ||
                          shaded_.environmentIntensity != before.environmentIntensity);
  if (shChanged)
    environmentSh_ = scene::environmentSh9(*shaded_.environmentMap, shaded_.environmentRotation, shaded_.environmentIntensity);
}

std::optional<scene::EnvironmentSun> Session::environmentSun() const {
  if (!separatedSun_ || shaded_.environmentMap != separatedSun_->sky) return std::nullopt;
  return separatedSun_->sun;
}

float autoExposureEv(const Lighting& l, float brightestEmission, float sceneScale) {
  // A white Lambertian surface facing the sun under the sky has radiance E/pi + L. Lights are
  // seen from a fifth of the scene's extent (2 m in a 10 m room): a distance of the scene's,
  // so the same scene at any scale gets the same exposure.
  const double seenFrom = 0.2 * std::max(double(sceneScale), 1e-30), seenFrom2 = seenFrom * seenFrom;
  double brightestLight = 0.0;
  for (const auto& light : l.lights) {
    if (light.hidden) continue;
    const double e = shared::tlLuminance(light.radiometric());
    // A point or spot light of intensity I lights a surface that far away with I / d^2; an area
    // light of radiance L and emitting area A as much as a point of intensity L A (its area seen
    // face on; a tube's side 2 r x length), and never more than pi L (a surface touching it).
    double area = 0.0;
    if (light.type == scene::LightType::Rect) area = double(light.width) * light.height;
    if (light.type == scene::LightType::Disk) area = glm::pi<double>() * light.radius * light.radius;
    if (light.type == scene::LightType::Tube) area = 2.0 * light.radius * light.length;
    const double seen = light.type == scene::LightType::Directional ? e
                        : scene::isAreaLight(light.type)           ? std::min(glm::pi<double>() * e, e * area / seenFrom2)
                                                                   : e / seenFrom2;
    brightestLight = std::max(brightestLight, seen);
  }
  const glm::vec3 sky = l.environmentMap ? l.environmentMap->meanRadiance * l.environmentIntensity : l.skyRadiance;
  double white = shared::tlLuminance(l.sunIrradiance) / glm::pi<double>() + shared::tlLuminance(sky) +
                 0.1 * brightestEmission + brightestLight / glm::pi<double>();
  return float(std::log2(std::max(white, 1e-3)));
}

float Session::exposureEv() const {
  return shaded_.exposureEv.value_or(autoExposureEv(shaded_, brightestEmission_, sceneSize().diagonal));
}

void Session::buildFrameConstants(shared::FrameConstants& fc, uint32_t frameNumber, bool jitter) const {
  const double aspect = double(settings_.width) / double(settings_.height);
  CameraMatrices cam = cameraMatrices(view_, aspect);
  if (jitter) {
    // TAA: shift the projection by this frame's sub-pixel offset (clip.xy += offset * clip.w);
    // positions rebuilt from depth use the same matrix, motion vectors subtract the offset.
    const glm::vec2 pixels = shared::tlTaaJitterPixels(frameNumber);
    const glm::dvec2 ndc(2.0 * pixels.x / settings_.width, 2.0 * pixels.y / settings_.height);
    glm::dmat4 shift(1.0);
    shift[3][0] = ndc.x;  // column 3 multiplies w
    shift[3][1] = ndc.y;
    cam.proj = shift * cam.proj;
    cam.viewProj = shift * cam.viewProj;
    fc.jitter = glm::vec4(float(ndc.x), float(ndc.y), 0.0f, 0.0f);
  }
  fc.view = glm::mat4(cam.view);
  fc.proj = glm::mat4(cam.proj);
  fc.viewProj = glm::mat4(cam.viewProj);
  fc.invViewProj = glm::mat4(glm::inverse(cam.viewProj));
  const View& prev = previousView_.value_or(view_);
  fc.prevViewProj = glm::mat4(previousViewProjRelative(prev, view_.position, aspect));

  glm::dvec3 travel = glm::normalize(shaded_.sunDirection);
  SunShadowFit fit = fitSunShadow(view_, aspect, scene_->bounds, travel, settings_.shadowMapSize);
  fc.sunViewProj = glm::mat4(fit.viewProj);
  fc.sunToLight = glm::vec4(glm::vec3(-travel), shaded_.sunAngularRadius);
  fc.sunIrradiance = glm::vec4(shaded_.sunIrradiance, 0.0f);
  fc.skyRadiance = glm::vec4(shaded_.skyRadiance, 0.0f);
  fc.viewport = glm::vec4(settings_.width, settings_.height, 1.0f / settings_.width, 1.0f / settings_.height);
  fc.shadowParams = glm::vec4(float(fit.texelWorld), float(fit.texelWorld * settings_.shadowDepthBiasTexels),
                              settings_.shadowNormalOffsetTexels, float(settings_.shadowMapSize));
  fc.shadowSoftness = glm::vec4(float(fit.depthRange), settings_.pcssMaxRadiusTexels, settings_.softShadows ? 1.0f : 0.0f, 0.0f);
  fc.exposure = std::exp2(-exposureEv());
  fc.frameIndex = frameNumber;
  fc.cameraAxis = glm::vec4(glm::vec3(view_.forward), view_.orthographic ? 1.0f : 0.0f);
  fc.flags = glm::length(shaded_.sunIrradiance) > 0.0f ? shared::kFrameFlagSunShadows : 0u;
  fc.flags |= uint32_t(settings_.materials) << shared::kFrameMaterialsShift;
  if (jitter) fc.flags |= shared::kFrameFlagFramesAveraged;
  fc.sceneScale = float(scene_->bounds.valid() ? glm::length(scene_->bounds.size()) : 1.0);
  if (scene_->bounds.valid()) {
    fc.sceneMin = glm::vec4(glm::vec3(scene_->bounds.min - view_.position), 0.0f);
    fc.sceneMax = glm::vec4(glm::vec3(scene_->bounds.max - view_.position), 0.0f);
  }
  fc.lightCount = 0;  // FramePipeline::importBuffers writes the light table and its count
  if (const auto& map = shaded_.environmentMap) {
    fc.flags |= shared::kFrameFlagEnvironment;
    fc.envWidth = map->width;
    fc.envHeight = map->height;
    fc.envParams = glm::vec4(std::cos(shaded_.environmentRotation), std::sin(shaded_.environmentRotation),
                             shaded_.environmentIntensity, 0.0f);
    for (size_t i = 0; i < environmentSh_.size(); ++i) fc.envSh[i] = environmentSh_[i];
  }
}

void Session::setFramesInFlight(uint32_t frames) {
  if (frames < 1 || frames > gpu::kMaxFramesInFlight)
    throw SessionError(fmt::format("frames in flight must be 1 to {}, not {}", gpu::kMaxFramesInFlight, frames));
  settle();
  framesInFlight_ = frames;
}

// The facade's part of a frame: which path renders it, its constants, the pose, the inputs
// every pass gets; FramePipeline adds the buffers and passes, then the graph is compiled and
// submitted with the read-backs this frame owes.
void Session::beginOne(bool readback) {
  // The oldest frame is collected first when the limit is reached: what the host writes for
  // this frame goes into buffers that frame (two frames back) used.
  while (inFlight_.size() >= framesInFlight_) finishOne();
  const uint64_t frame = executor_->nextFrame();
  // The Compare panel renders its sides and the reference in turn; each path sees its own
  // previous frame as "previous" (its history and motion vectors refer to it).
  lighting::LightingPath* path = path_;
  std::string compared;
  if (compare_) {
    compared = compare_->nextPath();
    path = findPath(compared);
    auto prev = comparePrevious_.find(compared);
    previousView_ = prev != comparePrevious_.end() ? std::optional<View>(prev->second) : std::nullopt;
  }
  // No motion vectors across a cut; the histories see it in the frame key and restart.
  if (previousView_ && isCameraCut(*previousView_, view_, scene_->bounds.valid() ? glm::length(scene_->bounds.size()) : 1.0))
    previousView_.reset();
  const bool taa = lighting::temporalAntialiasing(settings_, path->capabilities().rasterizes);
  // A compared path renders every second or third frame: its own count keeps its per-frame
  // patterns (the ray checkerboard, the 2x2 cycle, the blue-noise offset, TAA's jitter) moving.
  const uint32_t frameNumber = compare_ ? uint32_t(compareFrames_[compared]++) : uint32_t(frameIndex_);
  shared::FrameConstants fc{};
  buildFrameConstants(fc, frameNumber, taa);
  if (path->capabilities().debugView) fc.flags |= shared::kFrameFlagShowValues;  // its values as they are
  // Animated nodes move their instances first: the instance table, the top level, the voxel
  // regions and the frame key all see this frame's pose.
  std::vector<glm::dmat4> nodeWorld;
  if (!scene_->nodeAnimations.empty() || !scene_->skins.empty())
    nodeWorld = scene::nodeWorldTransformsAt(*scene_, animationTime_);
  movedLastFrame_ = scene_->nodeAnimations.empty() ? 0 : scene::poseInstances(*scene_, nodeWorld);
  gpuScene_->updateInstances(*scene_, view_.position, previousView_.value_or(view_).position, frame);
  applyDeformation(nodeWorld);
  historyLog_.clear();

  graph::RenderGraph graph;
  const FrameLights lights = pipeline_->importBuffers(graph, frame, fc, *gpuScene_, shaded_.lights,
                                                      shaded_.environmentMap.get(), scene_->bounds, view_.position, settings_);
  // The paths render with every automatic setting resolved against this scene's extent; the
  // frame key keeps the settings as set (0 = automatic), so only a real change restarts a history.
  frameSettings_ = lighting::resolveAutomatic(settings_, sceneSize());
  lighting::FrameInputs in{*device_, *gpuScene_, *scene_, frameSettings_, fc, view_.position, frame};
  in.historyValid = [this](std::string_view name, const graph::ResourceDesc& desc) {
    return executor_->historyValid(name, desc);
  };
  in.lastReadback = [this](std::string_view name) -> const graph::Readback* {
    auto it = executor_->readbacks().find(std::string(name));
    return it == executor_->readbacks().end() ? nullptr : &it->second;
  };
  in.historyResets = executor_->historyResets();
  in.instanceAlbedo = &albedo_->instanceAlbedo();
  in.instanceAlbedoVersion = albedo_->version();
  in.temporalAntialiasing = taa;
  in.pathName = path->name();
  in.key = frameKey(frameNumber);  // after applyDeformation: the geometry this frame shows
  in.historyLog = &historyLog_;
  FrameViews views;
  if (compare_) {
    const auto& v = compare_->view();
    views.compare = &v;
    views.compared = compared;
    views.hasLeft = compare_->hasImage(v.left) || compared == v.left;
    views.hasRight = compare_->hasImage(v.right) || compared == v.right;
  } else if (display_) {
    views.display = &*display_;
  }
  const std::string missing = pipeline_->addPasses(graph, in, *path, lights, views);
  if (views.display) displayMissing_ = missing;
  // What is read back is wanted: debug views nothing else reads (albedo.*) survive culling
  // in the frame that reads them, and a capture gets every buffer the frame can make.
  if (readback) {
    for (const auto& r : graph.resources())
      if (!r.imported && (requestAll_ || std::find(requested_.begin(), requested_.end(), r.name) != requested_.end()))
        graph.markOutput(r.name);
  }

  graph::CompiledGraph compiled = executor_->compile(graph);
  if (readback) {
    if (requestAll_) executor_->requestReadbackAll();
    for (auto& n : requested_) executor_->requestReadback(n);
    executor_->requestReadback(lighting::kCompositeHdr);
    executor_->requestReadback(lighting::kTonemapLdr);
  }
  if (compare_) executor_->requestReadback(lighting::compareImageName(compared));
  // The compare panel's figures against the converged reference need the reference's noise.
  const std::string noise = compare_ && compared == compare_->referencePath() ? findPath(compared)->capabilities().readouts.noise
                                                                               : std::string();
  if (!noise.empty()) executor_->requestReadback(noise);
  executor_->submit(graph, compiled);
  graphDump_ = graph.dump(compiled);
  if (readback) graphDot_ = graph.dot(compiled);
  InFlight begun{path, compared, compareGeneration_, in.key, fc.exposure, noise};
  for (auto& [name, value] : path->figures())
    if (name == "reference.samples") begun.referenceSamples = uint32_t(value);
  for (const auto& d : historyLog_)
    if (d.history == "reference.accumulation") begun.accumulation = d;
  inFlight_.push_back(std::move(begun));
  if (compare_) comparePrevious_[compared] = view_;
  previousView_ = view_;
  ++frameIndex_;
  animationTime_ += animationStep_;
}

void Session::finishOne() {
  if (inFlight_.empty()) return;
  const InFlight done = std::move(inFlight_.front());
  inFlight_.pop_front();
  executor_->finish();
  double total = 0.0;
  for (const auto& t : executor_->timings()) {
    total += t.gpuMs;
    auto it = std::find_if(passGpuMs_.begin(), passGpuMs_.end(), [&](auto& p) { return p.first == t.pass; });
    if (it == passGpuMs_.end()) it = passGpuMs_.insert(passGpuMs_.end(), {t.pass, {}});
    it->second.push_back(t.gpuMs);
  }
  frameGpuMs_.push_back(total);
  // The compare view it was rendered for may have been closed or replaced since.
  if (compare_ && !done.compared.empty() && done.compareGeneration == compareGeneration_) {
    compare_->frameDone(done.compared, executor_->readback(lighting::compareImageName(done.compared)), total, done.key,
                        done.referenceSamples, done.exposure, done.accumulation,
                        !done.noise.empty() && executor_->readbacks().count(done.noise) ? &executor_->readback(done.noise)
                                                                                        : nullptr);
  }
}

// Deforming meshes take this frame's pose, morph weights first, then the skin's joints (glTF's
// order): only those whose weights or joint matrices changed are uploaded. `nodeWorld`: every
// node's world transform at this frame's time (empty when the scene has no skins).
void Session::applyDeformation(const std::vector<glm::dmat4>& nodeWorld) {
  deformedLastFrame_ = 0;
  if (!scene_ || appliedWeights_.empty()) return;
  bool any = false;
  for (const auto& m : scene_->meshes) any |= m.deforms();
  if (!any) return;
  const auto weights = scene::morphWeightsAt(*scene_, animationTime_);
  std::vector<uint32_t> meshes;
  std::vector<std::vector<scene::Vertex>> vertices;
  for (const scene::Instance& instance : scene_->instances) {
    const uint32_t m = instance.mesh;
    const scene::Mesh& mesh = scene_->meshes[m];
    if (!mesh.deforms()) continue;
    std::vector<glm::mat4> joints;
    if (mesh.skinned() && instance.node < nodeWorld.size())
      joints = scene::jointMatrices(scene_->skins[size_t(mesh.skin)], nodeWorld[instance.node], nodeWorld);
    if (weights[m] == appliedWeights_[m] && joints == appliedJoints_[m]) continue;
    meshes.push_back(m);
    vertices.emplace_back();
    scene::deformVertices(mesh, weights[m], vertices.back());
    if (!joints.empty()) scene::skinVertices(mesh, joints, vertices.back());
    appliedWeights_[m] = weights[m];
    appliedJoints_[m] = std::move(joints);
  }
  // The upload replaces vertices (and last frame's positions) the frames in flight read: they
  // finish first.
  if (!meshes.empty() || gpuScene_->writesPending()) settle();
  gpuScene_->updateMeshVertices(meshes, vertices);
  deformedLastFrame_ = meshes.size();
}

void Session::beginFrame() {
  if (capture_ || !scene_) {
    renderFrames(1);  // a reopened capture's display is quick: done at once
    return;
  }
  beginOne(true);
  requested_.clear();
  requestAll_ = false;
}

bool Session::frameDone() const { return inFlight_.empty() || executor_->frameDone(); }

// The timings describe the frame collected last.
void Session::finishFrame() {
  if (inFlight_.empty()) return;
  frameGpuMs_.clear();
  passGpuMs_.clear();
  finishOne();
}

const graph::Readback* Session::displayReadback() const {
  auto it = executor_->readbacks().find(std::string(lighting::kDisplayLdr));
  return it == executor_->readbacks().end() ? nullptr : &it->second;
}

void Session::renderFrames(uint32_t n, const std::function<void(uint32_t done)>& afterEach) {
  settle();
  if (capture_) {
    if (!captureDisplay_) captureDisplay_ = std::make_unique<lighting::DisplayPass>();
    if (std::find(requested_.begin(), requested_.end(), lighting::kDisplayLdr) != requested_.end())
      executor_->requestReadback(lighting::kDisplayLdr);
    lighting::DisplayRequest request = display_.value_or(lighting::DisplayRequest{});
    displayMissing_.clear();
    if (!request.source.empty() && !hasBuffer(request.source)) displayMissing_ = request.source, request = {};
    capture_->display(*executor_, *captureDisplay_, request);
    requested_.clear();
    requestAll_ = false;
    return;
  }
  if (!scene_) throw SessionError("no scene is loaded");
  frameGpuMs_.clear();
  passGpuMs_.clear();
  // Frame i+1 is recorded while the GPU runs frame i (up to framesInFlight_ at once).
  for (uint32_t i = 0; i < n; ++i) {
    beginOne(i + 1 == n);
    if (afterEach) afterEach(i + 1);
  }
  settle();
  requested_.clear();
  requestAll_ = false;
}

std::optional<uint32_t> Session::instanceAt(uint32_t x, uint32_t y) const {
  const graph::Readback& ids = buffer(lighting::gbuffer::kInstanceId);
  if (x >= ids.extent.width || y >= ids.extent.height) return std::nullopt;
  uint32_t id;
  std::memcpy(&id, &ids.bytes[(size_t(y) * ids.extent.width + x) * 4], 4);
  if (id == 0 || id > scene().instances.size()) return std::nullopt;
  return id - 1;
}

const std::vector<graph::PhysicalInfo>& Session::resources() const {
  return capture_ ? capture_->resources() : executor_->resources();
}

const std::vector<graph::PassTiming>& Session::timings() const { return capture_ ? capture_->timings() : executor_->timings(); }

void Session::openCapture(const std::filesystem::path& dir) {
  auto opened = std::make_unique<CapturedFrame>(*device_, dir);  // throws, keeping what was open
  settle();
  device_->waitIdle();
  executor_->unbindImported();  // a capture open before this one is freed now
  capture_ = std::move(opened);
}

const scene::Scene* Session::decodingScene() const {
  if (capture_) return &capture_->decodingScene();
  return scene_.get();
}

void Session::closeCapture() {
  settle();
  device_->waitIdle();
  executor_->unbindImported();  // the capture's images are freed with it
  capture_.reset();
  // The capture's frames bound its images under the live resources' names (gbuffer.normal,
  // gbuffer.instanceId, ...): a fresh executor forgets those bindings, which would otherwise
  // outlive the images, and the live frame starts its resources and histories afresh.
  executor_ = std::make_unique<graph::Executor>(*device_);
}

const graph::Readback& Session::buffer(std::string_view name) const {
  if (capture_) return capture_->readback(std::string(name));
  try {
    return executor_->readback(name);
  } catch (const gpu::Error& e) {
    throw SessionError(e.what());
  }
}

bool Session::hasBuffer(std::string_view name) const {
  if (capture_) {
    const auto& r = capture_->resources();
    return std::any_of(r.begin(), r.end(), [&](auto& info) { return info.name == name; });
  }
  return executor_->readbacks().count(std::string(name)) != 0;
}

void Session::writeGraph(const std::filesystem::path& file) const {
  std::string ext = file.extension().string();
  for (auto& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  writeTextFile(file, ext == ".dot" || ext == ".gv" ? graphDot_ : graphDump_);
}

ImageWriteReport Session::saveImage(const std::filesystem::path& file) const {
  std::string ext = file.extension().string();
  for (auto& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".exr") return writeImageAtomically(file, buffer(lighting::kCompositeHdr), ImageEncoding::Linear);
  if (ext == ".png") return writeImageAtomically(file, buffer(lighting::kTonemapLdr), ImageEncoding::Display8);
  throw SessionError(fmt::format("{}: unsupported image type `{}` (use .exr or .png)", file.string(), ext));
}

lighting::SceneSize Session::sceneSize() const {
  if (!scene_ || !scene_->bounds.valid()) return {};
  const auto& b = scene_->bounds;
  const glm::dvec3 size = b.size();
  return {float(glm::length(size)), float(std::max({size.x, size.y, size.z}))};
}

}  // namespace tl::session
