// The frame's pass order, owned in one place. The session (the facade) decides what a frame
// shows — the path, the camera, the light, the settings, what is displayed — and FramePipeline
// turns that into the graph: the buffers the host writes for the frame (importBuffers), then
// the passes in order (addPasses):
//
//   gbuffer -> shadow.sun -> shadow.lights -> the lighting path -> lights.direct (the light
//   table; refined by redeferred shading inside the composite) -> composite -> taa ->
//   albedo view -> tonemap -> the compare view or the display
//
// A pass every path shares goes here; a path's own passes go in its addPasses
// (lighting/lighting_path.h).
#pragma once

#include "gpu/resources.h"
#include "gpu/upload_ring.h"
#include "graph/graph.h"
#include "lighting/common/display_pass.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/light_shadows.h"
#include "lighting/common/scene_accel.h"
#include "lighting/lighting_path.h"
#include "scene/environment_map.h"
#include "shared/lights.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tl::lighting {
class AlbedoViewPass;
struct CompareViewRequest;
}  // namespace tl::lighting

namespace tl::session {

// The light table as this frame shades it: the lights, nearest first, and the shadow map views
// of those that cast shadows (lighting/common/light_shadows.h).
struct FrameLights {
  std::vector<shared::GpuLight> lights;
  lighting::LightShadowPlan shadowPlan;
};

// What the frame shows besides the final image: the Compare panel's view (one side rendered
// this frame), or the editor's display.
struct FrameViews {
  const lighting::CompareViewRequest* compare = nullptr;
  std::string compared;  // the side this frame renders
  bool hasLeft = false, hasRight = false;  // the sides that have an image to show
  const lighting::DisplayRequest* display = nullptr;
};

class FramePipeline {
 public:
  explicit FramePipeline(gpu::Device& device);
  ~FramePipeline();

  // Pipelines depend on the scene's descriptor layout: a new scene gets new passes.
  void resetPasses();

  // Imports the buffers the host writes for frame `frame`: the frame constants (`fc`; its
  // lightCount is set here), the BRDF tables, the scene's tables, the light table and the light
  // shadow views (only with such lights), the environment map's table (only with a map).
  FrameLights importBuffers(graph::RenderGraph& graph, uint64_t frame, shared::FrameConstants& fc, scene::GpuScene& gpuScene,
                            const std::vector<scene::Light>& lights, const scene::EnvironmentMap* environmentMap,
                            const scene::Bounds& bounds, const glm::dvec3& camera, const lighting::RenderSettings& settings);

  // The frame's passes in order (above). Returns the resource the display was asked to show and
  // this frame does not make (it shows the final image instead), or "".
  std::string addPasses(graph::RenderGraph& graph, lighting::FrameInputs& in, lighting::LightingPath& path,
                        const FrameLights& lights, const FrameViews& views);

  lighting::AlbedoViewPass& albedoView();

 private:
  void uploadEnvironmentTable(const scene::EnvironmentMap& map);

  gpu::Device& device_;
  // The scene's acceleration structures, built once and lent to every tracer (FrameInputs::accel).
  lighting::SceneAccel accel_;
  struct Passes;
  std::unique_ptr<Passes> passes_;
  gpu::UploadRing constants_;
  gpu::Buffer brdfTables_;  // shared/brdf_lut.h BrdfTables, written once
  // The environment map's table (shared/environment.h), uploaded when the map changes; exists
  // only once a map was set.
  gpu::Buffer environmentTable_;
  uint64_t environmentTableHash_ = 0;
  gpu::UploadRing lightTable_;  // shared/lights.h GpuLight[], rewritten each frame; grows, exists once a scene has lights
  gpu::UploadRing lightShadowViews_;  // shared/lights.h GpuShadowView[] of point and spot light shadow maps, rewritten each frame
};

}  // namespace tl::session
