// What every pass of a frame gets when it adds itself to the graph: the device, the scene
// on the GPU, the frame's constants and the render settings. Frame-scoped: the graph is
// built, compiled and executed while these are alive.
#pragma once

#include "gpu/device.h"
#include "graph/executor.h"  // graph::Readback
#include "graph/graph.h"
#include "lighting/common/frame_key.h"
#include "lighting/common/render_settings.h"
#include "scene/gpu_scene.h"
#include "scene/scene.h"
#include "shared/frame.h"

#include <algorithm>
#include <functional>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tl::lighting {

class SceneAccel;

// Resources the frame imports from outside the graph: the session's constants, and the
// scene's buffers (named and imported by scene/gpu_scene.h, GpuScene::importBuffers).
inline constexpr graph::BufferName kFrameConstants{"frame.constants"};
// The shared BRDF's tables (shared/brdf_lut.h BrdfTables), uploaded once by the session: every
// pass that shades with shared/shading.h reads them at set 0 binding kBindingBrdfTables.
inline constexpr graph::BufferName kBrdfTables{"brdf.tables"};
using scene::kSceneIndices;
using scene::kSceneInstances;
using scene::kSceneMaterials;
using scene::kSceneVertices;

// Declares the reads of the frame constants and the scene's tables that every pass drawing
// or tracing the scene makes; `geometry` is how it reads the vertex and index buffers.
inline void readSceneInputs(graph::PassBuilder& b, graph::Usage geometry, bool materials = true) {
  b.read(kFrameConstants, graph::Usage::StorageRead);
  b.read(kSceneVertices, geometry);
  b.read(kSceneIndices, geometry);
  b.read(kSceneInstances, graph::Usage::StorageRead);
  if (materials) b.read(kSceneMaterials, graph::Usage::StorageRead);
}

struct FrameInputs {
  gpu::Device& device;
  scene::GpuScene& scene;
  const scene::Scene& sceneData;  // the CPU side: materials, textures, meshes (RT albedo, BLAS)
  const RenderSettings& settings;
  const shared::FrameConstants& constants;
  glm::dvec3 cameraWorld{0.0};  // the camera's world position (camera-relative space is centred on it)
  // The frame's number: what the host writes for this frame goes into that frame's copy of a
  // ring (gpu/upload_ring.h), as the frame before may still be running. A path imports what
  // it owns through the graph (RenderGraph::importBuffer) and asks for read-backs there too.
  uint64_t frame = 0;
  // The scene's acceleration structures, which every tracer borrows (lighting/common/scene_accel.h
  // traceStructures); the session's FramePipeline owns them and sets this.
  SceneAccel* accel = nullptr;
  // Whether a persistent resource holds last frame's contents with this description (the
  // executor's record; false after a reset, a resize or a frame that did not write it).
  std::function<bool(std::string_view name, const graph::ResourceDesc& desc)> historyValid;
  // What the last finished frame read back under `name`, or null (a path's own feedback,
  // e.g. the radiance cache's outcomes; up to a frame or two old with frames in flight).
  std::function<const graph::Readback*(std::string_view name)> lastReadback;
  // Changes whenever the session drops every history (Session::resetHistory: a new render,
  // a loaded scene): what a path measured over earlier frames no longer applies.
  uint64_t historyResets = 0;
  // Per-instance hit albedo resolved by the session (override > baked > texture average;
  // w: the source, shared/albedo.h kAlbedoSource*), and a counter that changes whenever any
  // value does; null: texture averages.
  const std::vector<glm::vec4>* instanceAlbedo = nullptr;
  // This frame is anti-aliased temporally (lighting/common/taa_pass.h): the projection is
  // jittered and the composite writes composite.unresolved for the TAA pass to resolve.
  bool temporalAntialiasing = false;
  std::string pathName;  // the lighting path this frame renders (per-path state such as TAA's history)
  uint64_t instanceAlbedoVersion = 0;
  // What this frame shows, in named parts: every history decides from it what it keeps
  // (lighting/common/frame_key.h), and writes its decision into the log (may be null).
  FrameKey key;
  std::vector<HistoryDecision>* historyLog = nullptr;
  // Views of point, spot and area light shadow maps this frame (lighting/common/light_shadows.h):
  // with any, "lights.shadowViews" is imported and "shadow.lightsDepth" can be drawn for who reads it.
  uint32_t lightShadowViews = 0;
  // The table's area lights: their glossy reflection and their shadows are sampled, so
  // lights.direct accumulates its estimate while nothing it depends on changes.
  uint32_t areaLights = 0;
  // The most radiance a white Lambertian surface reflects from the whole light table (each
  // point or spot light taken at a twentieth of the scene's size, an area light's radiance, a
  // directional light's E / pi): what the RT radiance cache's fixed-point sums must hold.
  float lightTableRadiance = 0.0f;
  // Redeferred below full rate: adds the light table's refining run (lights.direct.refine, the
  // pixels ibuffer.upsample could not fill), which whoever added lights.direct owns.
  std::function<void(graph::RenderGraph&)> refineLights;

  // An image the size of the frame's (settings.width x height), as graph::ResourceDesc::image2D
  // makes it (with `mips` levels): what a full-resolution pass states instead of the numbers.
  graph::ResourceDesc screenImage(VkFormat format, std::string what, uint32_t mips = 1) const {
    return graph::ResourceDesc::image2D(format, settings.width, settings.height, std::move(what), mips);
  }
};

}  // namespace tl::lighting
