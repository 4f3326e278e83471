// What every pass of a frame gets when it adds itself to the graph: the device, the scene
// on the GPU, the frame's constants and the render settings. Frame-scoped: the graph is
// built, compiled and executed while these are alive.
#pragma once

#include "gpu/device.h"
#include "graph/executor.h"
#include "graph/graph.h"
#include "lighting/common/frame_key.h"
#include "scene/gpu_scene.h"
#include "scene/scene.h"
#include "shared/frame.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tl::lighting {

// Material override modes (shared/material_mode.h): every path and the reference shade the
// scene as authored, or all Lambertian with the authored base colour (diffuse) or 0.8 grey (clay).
enum class MaterialMode : uint32_t {
  Authored = shared::kMaterialsAuthored,
  Diffuse = shared::kMaterialsDiffuse,
  Clay = shared::kMaterialsClay,
};
inline constexpr MaterialMode kMaterialModes[] = {MaterialMode::Authored, MaterialMode::Diffuse, MaterialMode::Clay};
inline const char* materialModeName(MaterialMode m) {
  switch (m) {
    case MaterialMode::Diffuse: return "diffuse";
    case MaterialMode::Clay: return "clay";
    default: return "authored";
  }
}
inline std::optional<MaterialMode> parseMaterialMode(std::string_view name) {
  for (MaterialMode m : kMaterialModes)
    if (name == materialModeName(m)) return m;
  return std::nullopt;
}

struct RenderSettings {
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t shadowMapSize = 2048;
  float shadowDepthBiasTexels = 1.5f;  // constant bias, in shadow-map texels of depth
  float shadowNormalOffsetTexels = 1.0f;
  bool softShadows = true;            // PCSS: penumbrae from the sun's angular size (else 3x3 PCF)
  float pcssMaxRadiusTexels = 16.0f;  // widest PCSS filter
  bool specularGi = true;             // indirect specular from a path's SH (Metro); else the sky's, times AO
  bool taa = false;                   // temporal anti-aliasing: jittered projection, YCoCg-clipped history (not the reference)
  float taaBlend = 0.1f;              // TAA: weight of the current frame in the exponential history
  MaterialMode materials = MaterialMode::Authored;  // material override mode, every path and the reference
  // Reference path tracer: scattering events per path (1 = direct light only: sun, sky,
  // emitters; 2 = plus one indirect bounce; ...) and samples per pixel added each frame.
  // Russian roulette ends paths from the fourth event on (shaders/reference/path.glsl); this
  // hard cap is high enough that raising it changes no image (docs/accuracy.md).
  uint32_t referenceBounces = 64;
  uint32_t referenceSamplesPerFrame = 1;

  // Ray-traced path (T5). Distances <= 0 mean "scaled to the scene" (see rt_path.cpp).
  float rtSimplifyRatio = 0.25f;    // RT (BLAS) mesh triangles / source triangles; 1 = full mesh
  float rtSimplifyError = 0.01f;    // largest deviation the simplifier may introduce, fraction of the mesh size
  float rtAoRadius = 0.0f;          // RTAO radius (m)
  float rtRayLength = 0.0f;         // GI ray length (m)
  float rtBlendDistance = 0.0f;     // beyond this view distance RT GI fades to the fallback (Metro: 250 m)
  bool rtPretrace = true;           // screen-space pre-trace before real rays
  bool rtHalfRays = false;          // 0.5 rays per pixel: a checkerboard alternating each frame
  bool rtHalfResolution = false;    // 0.25: trace at half resolution (one pixel of each 2x2, cycling),
                                    // depth-aware noisy upsampling into the accumulation; wins over rtHalfRays
  bool rtTwoRays = false;           // 2 rays per traced pixel (pre-trace, trace and hit lighting run twice)
  bool rtDenoise = true;            // two-pass spatial denoiser on the SH after accumulation
  float rtDenoiseRadius = 0.0f;     // pass 1 base radius (m); pass 2 uses half (Metro: 6 m and 3 m)
  bool rtScreenRadiance = true;     // hits seen on screen last frame reuse its shaded radiance (multi-bounce)
  bool rtHitSky = true;             // hits lit afresh (off screen) also see the sky, through one more ray
  bool rtEmitterSampling = true;    // emissive triangles sampled at pixels and hits (shadow rays), not found by chance
  uint32_t rtPretraceSteps = 16;
  float rtPretracePixels = 0.0f;    // screen length of a pre-traced ray; 0: scaled to the image (pretraceAutoPixels)
  float rtThickness = 0.02f;        // depth-buffer surface thickness, fraction of view distance
  uint32_t rtMaxAccumFrames = 32;   // temporal accumulation window
  float rtFireflyClamp = 0.0f;      // a sample's luma above this multiple of its neighbourhood's / history's RMS is clipped (0: off)
  bool rtLumaRejection = true;      // when the light changes, clip the history to this frame's samples (no ghosting)
  uint32_t rtDisocclusionRays = 0;  // rays per 8x8 cell holding a pixel whose history was rejected (RE ENGINE; 0: off)
  float rtCullAngle = 0.002f;       // contribution culling: instances subtending less (radians) are dropped
  float rtCullMargin = 0.0f;        // expanded frustum: margin (m) around the view frustum
  // Beyond the blend distance, the legacy path's GI (Metro) rather than the unoccluded sky;
  // it runs only when part of the scene lies that far from the camera.
  bool rtFarLegacy = true;
  // Deforming meshes' BLAS refits per frame (Metro): the highest priorities, random others,
  // and a vertex budget (the first pick always goes).
  uint32_t rtRefitTop = 16;
  uint32_t rtRefitRandom = 4;
  uint32_t rtRefitVertexBudget = 1u << 20;
  bool rtRawRayProbe = false;

  // Legacy path (T3). Distances <= 0 mean "scaled to the scene" (see legacy_path.cpp).
  float legacyAoRadius = 0.0f;      // SSAO / voxel AO radius (m)
  float legacyAoThickness = 0.1f;   // GTAO thickness heuristic, 0 (infinitely thick) .. 1 (paper thin)
  uint32_t legacyAoSlices = 1;     // GTAO's one slice per pixel and frame: the 2x2 interleave and the
  uint32_t legacyAoSteps = 4;      // 8-frame accumulation supply the directions (docs/performance.md)
  uint32_t legacyAoDivisor = 2;     // SSAO resolution: 1 full, 2 half
  uint32_t legacyConeDivisor = 4;   // cone tracing resolution: 1 full, 2 half, 4 quarter
  bool legacyVoxelizeEveryFrame = false;  // rebuild the voxels even when nothing they hold changed
  bool legacyPartialVoxels = true;  // deforming or moved instances re-voxelize only the voxels they reach
  bool legacyScreenRadiance = true; // voxels seen last frame take its shaded radiance (multi-bounce)
  uint32_t legacySettleFrames = 4;  // after a change, rebuild this many more frames so bounces settle
  uint32_t legacyAoFrames = 8;      // SSAO temporal accumulation window (1: off)
  uint32_t legacyVoxelResolution = 64;  // R: voxels per clipmap level side
  float legacyLevel0Extent = 0.0f;  // side of the finest clipmap level (m)
  uint32_t legacyMaxLevels = 4;
  float legacyConeRange = 0.0f;     // cones stop after this distance (m)
  float legacyConeStep = 1.0f;      // cone step as a fraction of its diameter       // benchmark: also trace the same rays with a trivial kernel (rt.rawRays)
};

// Defaults that scale with the scene (sceneScale: the diagonal of its bounds, metres), shared
// by the paths and the editor's lighting panel: an AO radius of 5% of the scene between
// 0.1 and 1 m (Metro's SSAO reached about 1 m), rays and cones as long as the scene up to
// Metro's 50 m (which also bounds how far outside the view the RT top level keeps instances).
inline float sceneScaledAoRadius(float sceneScale) { return std::clamp(0.05f * sceneScale, 0.1f, 1.0f); }
inline float sceneScaledRayLength(float sceneScale) { return std::clamp(sceneScale, 1e-3f, 50.0f); }
// The pre-trace's march in pixels when not set: a constant share of the image height (128 px
// at 360 lines), so it covers the same part of the view at any resolution.
inline float pretraceAutoPixels(uint32_t height) { return std::max(16.0f, float(height) * (128.0f / 360.0f)); }
inline float sceneScaledBlendDistance(float sceneScale) { return 2.0f * std::max(sceneScale, 1e-3f); }

// Resources the frame imports from outside the graph: the session's constants, and the
// scene's buffers (named and imported by scene/gpu_scene.h, GpuScene::importBuffers).
inline constexpr const char* kFrameConstants = "frame.constants";
// The shared BRDF's tables (shared/brdf_lut.h BrdfTables), uploaded once by the session: every
// pass that shades with shared/shading.h reads them at set 0 binding kBindingBrdfTables.
inline constexpr const char* kBrdfTables = "brdf.tables";
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
  gpu::Buffer& constantsBuffer;
  graph::Executor& executor;  // where a path binds buffers it owns and imports into the graph
  glm::dvec3 cameraWorld{0.0};  // the camera's world position (camera-relative space is centred on it)
  // Per-instance hit albedo resolved by the session (T7: override > baked > texture average;
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
};

}  // namespace tl::lighting
