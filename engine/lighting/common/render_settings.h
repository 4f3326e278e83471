// The render settings, declared once. Each line of TL_RENDER_SETTINGS is one setting: its C++
// type, name, default, valid range, unit, owner (a lighting path, or `common`), the lighting
// paths whose history it resets, flags and a one-line help. From this list come the
// RenderSettings struct, the schema below (JSON and `--set` with range checks, the editor's
// panels, `twinlight settings`, the docs' reference table) and each path's history settings
// (the frame key's `settings` part): a new setting of the engine is one line here. A plugin
// declares its own settings in its folder (PluginSetting, below): they join the same schema.
#pragma once

#include "shared/material_mode.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
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

// Setting flags (the `flags` column).
inline constexpr uint32_t kSettingPlain = 0;
inline constexpr uint32_t kSettingPow2 = 1u << 0;     // a power of two within the range (1/2, 1/4 for a number)
inline constexpr uint32_t kSettingAuto = 1u << 1;     // 0 means "derived from the scene or the image" (autoSettingValue)
inline constexpr uint32_t kSettingNoPanel = 1u << 2;  // set elsewhere (image size: --size, the render scale; probes)
// `twinlight tune` searches it (session/tune_space.h): a switch's two values, or its default
// times 1/4 .. 4 within the range. Windows of accumulation are not tuned: a still image's error
// cannot see what they cost (ghosts), so a tuner would always lengthen them.
inline constexpr uint32_t kSettingTune = 1u << 3;
// A feature a scene may not need: its switch off, or its range's minimum (its maximum with
// kSettingOffAtMax), leaves it out. `tune` tries its chosen presets without each.
inline constexpr uint32_t kSettingFeature = 1u << 4;
inline constexpr uint32_t kSettingOffAtMax = 1u << 5;

// X(type, name, default, min, max, unit, owner, resets history of, flags, help)
// Distances flagged kSettingAuto are "scaled to the scene" at 0 (see autoSettingValue).
// History: what a path's accumulated samples estimate restarts it; the ray pattern, the
// accumulation window, denoisers and update policies change only noise, weights or work
// (docs/design/frame-key.md). Redeferred shading changes how the composite
// applies light, downstream of every path's history: it resets none (its own light sums keep
// their own accumulation images).
// clang-format off
#define TL_RENDER_SETTINGS(X) \
  X(uint32_t, width, 640, 1, 16384, "px", "common", "", kSettingNoPanel, "image width (--size)") \
  X(uint32_t, height, 360, 1, 16384, "px", "common", "", kSettingNoPanel, "image height (--size)") \
  X(MaterialMode, materials, MaterialMode::Authored, 0, 2, "", "common", "reference rt legacy direct", kSettingPlain, "material override, every path and the reference: authored, diffuse (Lambert, authored base colour) or clay (Lambert 0.8 grey); emission stays") \
  X(uint32_t, shadowMapSize, 2048, 64, 8192, "texels", "common", "", kSettingTune, "side of the sun's shadow map") \
  X(float, shadowDepthBiasTexels, 1.5f, 0.0f, 16.0f, "texels", "common", "", kSettingPlain, "sun shadow constant depth bias, in shadow-map texels of depth") \
  X(float, shadowNormalOffsetTexels, 1.0f, 0.0f, 16.0f, "texels", "common", "", kSettingPlain, "sun shadow lookup offset along the normal, in shadow-map texels") \
  X(bool, softShadows, true, 0, 1, "", "common", "", kSettingTune, "PCSS: penumbrae from the sun's angular size (off: 3x3 PCF, --hard-shadows)") \
  X(float, pcssMaxRadiusTexels, 16.0f, 0.0f, 64.0f, "texels", "common", "", kSettingPlain, "widest PCSS filter") \
  X(uint32_t, lightShadowMapSize, 512, 64, 4096, "texels", "common", "legacy direct", kSettingTune, "side of each shadow-map view of a point, spot or area light (a point or area light has six; direct and legacy paths)") \
  X(uint32_t, lightShadowMaxLights, 8, 0, 32, "", "common", "legacy direct", kSettingPlain, "the most powerful point, spot and area lights that cast shadows in the direct and legacy paths (0: none; rt and the reference trace every light)") \
  X(bool, specularGi, true, 0, 1, "", "common", "", kSettingTune | kSettingFeature, "indirect specular from the path's SH (dominant direction, GGX; Metro); off: the sky's specular times AO") \
  X(bool, redeferred, false, 0, 1, "", "common", "", kSettingPlain, "redeferred shading (Fools Engine): lights accumulate material-free sums (ibuffer.*), one material pass applies the materials; off: the deferred composite") \
  X(float, redeferredRate, 1.0f, 0.25f, 1.0f, "", "common", "", kSettingPow2, "redeferred: share of pixels the illumination passes shade first (1 all, 0.5 a checkerboard, 0.25 one of each 2x2); the rest filled depth- and normal-aware, edges of geometry and light shaded at full rate") \
  X(bool, taa, false, 0, 1, "", "common", "", kSettingPlain, "temporal anti-aliasing: jittered projection, YCoCg-clipped history (not the reference, which jitters its own rays)") \
  X(float, taaBlend, 0.1f, 0.01f, 1.0f, "", "common", "", kSettingPlain, "TAA: weight of the new frame in the history; lower is smoother and slower to follow") \
  X(uint32_t, referenceBounces, 64, 1, 64, "events", "reference", "reference", kSettingPlain, "scattering events per path (1 = direct light only, 2 = one indirect bounce); Russian roulette ends paths first") \
  X(uint32_t, referenceSamplesPerFrame, 1, 1, 1024, "spp", "reference", "", kSettingPlain, "samples per pixel added each frame (render --spp sets it)") \
  X(bool, referenceEmitterSampling, true, 0, 1, "", "reference", "reference", kSettingPlain, "emissive triangles drawn by power at every scattering event (next-event estimation, power heuristic against the BRDF's rays); off: found only by rays that hit them") \
  X(uint32_t, referenceAdaptive, 0, 0, 2, "", "reference", "reference", kSettingPlain, "where each frame's samples go: 0 every pixel alike; 1 in proportion to each pixel's noise as an independent pilot measures it (unbiased; loses where rare paths carry the noise: docs/design/reference.md); 2 by the estimate's own samples (biased: a diagnostic)") \
  X(float, rtSimplifyRatio, 0.25f, 0.01f, 1.0f, "x", "rt", "rt", kSettingTune, "RT (BLAS) mesh triangles / source triangles (Metro: about 4x fewer); 1 = the full mesh") \
  X(float, rtSimplifyError, 0.01f, 0.0f, 1.0f, "x size", "rt", "rt", kSettingPlain, "largest deviation the simplifier may introduce, as a fraction of the mesh's size") \
  X(float, rtAoRadius, 0.0f, 0.0f, 1e9f, "m", "rt", "rt reference", kSettingAuto, "RTAO radius: a hit closer than this occludes (also the reference's AO)") \
  X(float, rtRayLength, 0.0f, 0.0f, 1e9f, "m", "rt", "rt", kSettingAuto, "GI rays stop after this distance; also the top level's culling margin") \
  X(float, rtBlendDistance, 0.0f, 0.0f, 1e9f, "m", "rt", "rt", kSettingAuto, "beyond this view distance RT GI fades to the far field (Metro: 250 m); the top level culls instances beyond it") \
  X(bool, rtFarLegacy, true, 0, 1, "", "rt", "", kSettingPlain, "the far field beyond the blend distance is the legacy path's voxel GI (Metro), else the unoccluded sky") \
  X(bool, rtPretrace, true, 0, 1, "", "rt", "rt", kSettingTune | kSettingFeature, "screen-space pre-trace: march the depth buffer first, real rays only where it finds nothing") \
  X(uint32_t, rtPretraceSteps, 16, 1, 256, "steps", "rt", "rt", kSettingTune, "depth samples along a pre-traced ray") \
  X(float, rtPretracePixels, 0.0f, 0.0f, 16384.0f, "px", "rt", "rt", kSettingAuto, "screen length of a pre-traced ray (auto: 128 px per 360 lines of the image)") \
  X(float, rtThickness, 0.02f, 0.0f, 1.0f, "x distance", "rt", "rt", kSettingPlain, "assumed thickness of what the depth buffer shows, as a fraction of its view distance") \
  X(bool, rtHalfRays, false, 0, 1, "", "rt", "", kSettingTune, "0.5 rays per pixel: a checkerboard that alternates each frame; the other half borrows a neighbour's ray") \
  X(bool, rtHalfResolution, false, 0, 1, "", "rt", "", kSettingTune, "0.25 rays per pixel: one pixel of each 2x2, cycling, depth-aware noisy upsampling (INSIDE); wins over rtHalfRays") \
  X(bool, rtTwoRays, false, 0, 1, "", "rt", "", kSettingTune, "2 rays per traced pixel (pre-trace, trace and hit lighting run twice; twice the cost, half the variance)") \
  X(uint32_t, rtMaxAccumFrames, 32, 1, 1024, "frames", "rt", "", kSettingPlain, "temporal accumulation window while the camera holds still") \
  X(float, rtFireflyClamp, 0.0f, 0.0f, 1e6f, "x RMS", "rt", "rt", kSettingPlain, "a sample's luma above this multiple of its neighbourhood's / history's RMS is clipped, in linear space (0: off)") \
  X(bool, rtLumaRejection, true, 0, 1, "", "rt", "", kSettingPlain, "when the light changes, clip each pixel's history to this frame's samples around it (no ghosting; RE ENGINE)") \
  X(uint32_t, rtDisocclusionRays, 0, 0, 64, "rays", "rt", "", kSettingTune, "rays per 8x8 cell holding a pixel whose history was rejected (RE ENGINE; 0: off)") \
  X(bool, rtDenoise, true, 0, 1, "", "rt", "", kSettingTune | kSettingFeature, "two-pass spatial denoiser on the SH after accumulation (Metro's)") \
  X(float, rtDenoiseRadius, 0.0f, 0.0f, 1e9f, "m", "rt", "", kSettingAuto, "denoiser pass 1 base radius; pass 2 uses half (Metro: 6 m and 3 m)") \
  X(bool, rtScreenRadiance, true, 0, 1, "", "rt", "rt", kSettingTune | kSettingFeature, "hits seen on screen last frame reuse its shaded radiance, so light bounces more than once") \
  X(bool, rtHitSky, true, 0, 1, "", "rt", "rt", kSettingTune | kSettingFeature, "hits lit afresh (off screen) also see the sky, through one more ray") \
  X(float, rtCacheMinGain, 0.02f, 0.0f, 2.0f, "share", "rt", "", kSettingTune | kSettingFeature | kSettingOffAtMax, "radiance cache: runs while the light it adds (bounces off surfaces off screen) is at least this share of the bounced light, measured every frame; stops below half of it (0: always; above 1: never)") \
  X(uint32_t, rtCachePaths, 4096, 16, 1u << 20, "paths", "rt", "", kSettingTune, "radiance cache: update paths a frame, at least (one pixel of each square tile that gives this many starts one)") \
  X(uint32_t, rtCacheBounces, 8, 1, 8, "rays", "rt", "", kSettingTune, "radiance cache: rays of an update path at most; from the third on a path goes on with the probability of its surface's albedo (Russian roulette), and where it ends it reads the cache, so light bounces on from frame to frame") \
  X(uint32_t, rtCacheMaxSamples, 64, 1, 65536, "samples", "rt", "", kSettingPlain, "radiance cache: a cell averages at most this many samples (fewer: follows changes sooner, noisier)") \
  X(float, rtCacheCellAngle, 0.03f, 0.001f, 1.0f, "rad", "rt", "", kSettingPlain, "radiance cache: a cell is at least this angle times its distance from the camera across") \
  X(float, rtCacheCellSize, 0.0f, 0.0f, 1e9f, "m", "rt", "", kSettingAuto, "radiance cache: the smallest cell (auto: the scene's size / 1000)") \
  X(uint32_t, rtCacheEntries, 1u << 16, 1u << 10, 1u << 24, "cells", "rt", "", kSettingPow2, "radiance cache: hash table slots (32 + 48 bytes each)") \
  X(float, rtReflectionRoughness, 0.5f, 0.0f, 1.0f, "roughness", "rt", "", kSettingTune | kSettingFeature, "reflections: pixels below this roughness trace one specular ray a frame (GGX visible normals), blended into the SH specular over the top fifth of the range; 0: no traced reflections, the SH specular everywhere") \
  X(float, rtMirrorRoughness, 0.02f, 0.0f, 1.0f, "roughness", "rt", "", kSettingPlain, "reflections: at or below this roughness the ray is the perfect reflection and the image is not filtered across pixels (RE ENGINE's mirrors)") \
  X(uint32_t, rtReflectionFrames, 16, 1, 1024, "frames", "rt", "", kSettingPlain, "reflections: temporal accumulation window (reprojected by the reflected point's virtual position)") \
  X(float, rtReflectionClamp, 1.5f, 0.1f, 100.0f, "sigma", "rt", "", kSettingPlain, "reflections: the history is clamped to this many standard deviations around this frame's 3x3 neighbourhood (what moved in a mirror leaves no ghost; larger: less noise, longer ghosts)") \
  X(float, rtReflectionFilterRadius, 8.0f, 0.0f, 64.0f, "px", "rt", "", kSettingPlain, "reflections: the spatial filter's largest radius (its footprint follows hit distance x roughness)") \
  X(uint32_t, rtReflectionRoughDivisor, 1, 1, 2, "", "rt", "", kSettingPow2 | kSettingTune, "reflections: rays for pixels above the mirror threshold, 1 every frame, 2 on a checkerboard flipped each frame (the temporal pass fills the others from their history and traced neighbours); mirrors trace every frame") \
  X(bool, rtEnvironmentSampling, true, 0, 1, "", "rt", "rt", kSettingTune | kSettingFeature, "with an environment map, each traced pixel also takes a shadow ray towards a direction drawn by the map's importance, weighed against its GI ray by MIS: the pixel sees the map's texels, not its order-2 SH") \
  X(bool, rtEmitterSampling, true, 0, 1, "", "rt", "rt", kSettingTune | kSettingFeature, "emissive triangles are sampled at pixels and hits through shadow rays, not found only by chance") \
  X(float, rtCullAngle, 0.002f, 0.0f, 3.14159f, "rad", "rt", "rt", kSettingTune, "contribution culling: instances subtending less are left out of the top level") \
  X(float, rtCullMargin, 0.0f, 0.0f, 1e9f, "m", "rt", "rt", kSettingAuto, "expanded frustum: margin around the view frustum within which instances stay in the top level (a visible point's ray reaches that far)") \
  X(uint32_t, rtRefitTop, 16, 0, 65536, "meshes", "rt", "", kSettingPlain, "deforming meshes whose BLAS is refitted each frame: the highest priorities (Metro: 16)") \
  X(uint32_t, rtRefitRandom, 4, 0, 65536, "meshes", "rt", "", kSettingPlain, "plus this many others drawn at random, so none waits forever (Metro: 4)") \
  X(uint32_t, rtRefitVertexBudget, 1u << 20, 0, 1u << 30, "vertices", "rt", "", kSettingPlain, "vertices refitted per frame at most (the first pick always goes)") \
  X(bool, hybridShadows, true, 0, 1, "", "rt", "", kSettingTune | kSettingFeature, "hybrid ray-traced sun shadows (GameWorks HRTS): a ray's hard shadow near contacts, PCSS further away, blended by blocker distance (shadow.sun.visibility); off: the shadow map alone") \
  X(float, hybridShadowHardTexels, 4.0f, 0.5f, 64.0f, "texels", "rt", "", kSettingPlain, "HRTS: penumbrae narrower than this many shadow-map texels take the ray's hard shadow; linear blend up to it") \
  X(bool, rtRawRayProbe, false, 0, 1, "", "rt", "", kSettingNoPanel, "benchmark: also trace the same rays with a trivial kernel (rt.rawRays; bench --rays)") \
  X(bool, referenceRawRayProbe, false, 0, 1, "", "reference", "", kSettingNoPanel, "benchmark: also trace a trivial kernel on the reference's top level (reference.rawRays; bench --rays)") \
  X(float, legacyAoRadius, 0.0f, 0.0f, 1e9f, "m", "legacy", "legacy", kSettingAuto, "reach of SSAO and voxel AO") \
  X(float, legacyAoThickness, 0.1f, 0.0f, 1.0f, "", "legacy", "legacy", kSettingPlain, "GTAO thickness heuristic: how fast a horizon falls back behind thin occluders (0 infinitely thick, 1 paper thin)") \
  X(uint32_t, legacyAoSlices, 1, 1, 16, "slices", "legacy", "legacy", kSettingTune, "GTAO slice directions per pixel and frame (the 2x2 interleave and the accumulation supply more)") \
  X(uint32_t, legacyAoSteps, 4, 1, 64, "samples", "legacy", "legacy", kSettingTune, "GTAO depth samples per direction and side") \
  X(uint32_t, legacyAoDivisor, 2, 1, 2, "", "legacy", "legacy", kSettingPow2 | kSettingTune, "SSAO resolution divisor: 1 full, 2 half") \
  X(uint32_t, legacyAoFrames, 8, 1, 64, "frames", "legacy", "", kSettingPlain, "SSAO temporal accumulation window (1: off)") \
  X(uint32_t, legacyConeDivisor, 4, 1, 4, "", "legacy", "", kSettingPow2 | kSettingTune, "cone tracing resolution divisor: 1 full, 2 half, 4 quarter") \
  X(uint32_t, legacyVoxelResolution, 64, 8, 256, "voxels", "legacy", "legacy", kSettingPow2 | kSettingTune, "clipmap resolution R: each level holds R^3 voxels") \
  X(float, legacyLevel0Extent, 0.0f, 0.0f, 1e9f, "m", "legacy", "legacy", kSettingAuto, "side of the finest clipmap level; coarser levels double it until the scene is covered") \
  X(uint32_t, legacyMaxLevels, 4, 1, 4, "levels", "legacy", "legacy", kSettingTune, "clipmap levels at most") \
  X(float, legacyConeRange, 0.0f, 0.0f, 1e9f, "m", "legacy", "", kSettingAuto, "cones stop after this distance") \
  X(float, legacyConeStep, 1.0f, 0.2f, 2.0f, "x diameter", "legacy", "", kSettingTune, "cone step as a fraction of its diameter: smaller is slower and more exact") \
  X(uint32_t, legacyRoomSweeps, 4, 0, 64, "rounds", "legacy", "legacy", kSettingTune | kSettingFeature, "rooms: rounds of x, y and z sweeps that flood the finest level's air from its lit surfaces and open edges; cones in air no light reaches (a sealed room) gather nothing (0: off)") \
  X(bool, legacyScreenRadiance, true, 0, 1, "", "legacy", "legacy", kSettingTune | kSettingFeature, "voxels seen last frame take its shaded radiance, so light bounces more than once") \
  X(float, legacyReflectionRoughness, 0.5f, 0.0f, 1.0f, "roughness", "legacy", "", kSettingTune | kSettingFeature, "reflections: pixels below this roughness follow their mirror direction across the screen (last frame's image, through a hierarchical depth march) and through the voxels (a specular cone the lobe's width), blended into the SH specular over the top fifth of the range; 0: the SH specular everywhere") \
  X(uint32_t, legacyReflectionSteps, 64, 0, 1024, "steps", "legacy", "", kSettingTune, "reflections: the screen-space march's steps at most (0: the voxel cone alone)") \
  X(bool, legacyPartialVoxels, true, 0, 1, "", "legacy", "", kSettingPlain, "deforming or moved instances re-voxelize only the voxels they and their shadows reach") \
  X(bool, legacyVoxelizeEveryFrame, false, 0, 1, "", "legacy", "", kSettingPlain, "rebuild the voxels every frame, even when nothing they hold changed") \
  X(uint32_t, legacySettleFrames, 4, 0, 64, "frames", "legacy", "", kSettingPlain, "after a change, rebuild the voxels this many more frames so bounces settle")
// clang-format on

// The values of the settings plugins declare (PluginSetting), by the slot each registration
// got. NaN is a value never set, which stands for the setting's default: the defaults are
// known only once the plugins have registered, after these arrays may have been made.
inline constexpr size_t kMaxPluginSettings = 32;
using PluginSettingValues = std::array<double, kMaxPluginSettings>;
constexpr PluginSettingValues unsetPluginSettings() {
  PluginSettingValues v{};
  for (double& x : v) x = std::numeric_limits<double>::quiet_NaN();
  return v;
}

struct RenderSettings {
#define TL_SETTING_MEMBER(type, name, def, ...) type name = def;
  TL_RENDER_SETTINGS(TL_SETTING_MEMBER)
#undef TL_SETTING_MEMBER
  PluginSettingValues pluginValues = unsetPluginSettings();  // read through the plugin's PluginSetting
};

// A plugin setting's stored value: its slot's, or `fallback` (its default) where never set.
inline double pluginSettingValue(const RenderSettings& settings, uint32_t slot, double fallback) {
  const double v = settings.pluginValues[slot];
  return std::isnan(v) ? fallback : v;
}

enum class SettingType { Bool, UInt, Float, Enum };

// What automatic values derive from: the scene's size in its own units.
struct SceneSize {
  float diagonal = 1.0f;     // of its bounds (FrameConstants::sceneScale)
  float largestSide = 1.0f;  // of its bounds
};

// One setting as the schema knows it. `get`/`set` read and write it as a double (a bool as 0 or
// 1, the material mode as its index in `choices`); `set` takes a value already checked.
struct SettingInfo {
  std::string_view name;
  SettingType type;
  double defaultValue, min, max;
  std::string_view unit;
  std::string_view owner;    // "common" or a lighting path's name (a plugin's, for its own settings)
  // Space-separated names of the paths whose history it resets; a plugin's path adds itself
  // to an engine setting's with registerHistoryInputs, so this column never names a plugin.
  std::string_view history;
  uint32_t flags;
  std::string_view help;
  std::vector<std::string_view> choices;  // names of an enum's values, in order
  std::function<double(const RenderSettings&)> get;
  std::function<void(RenderSettings&, double)> set;
  // kSettingAuto: what 0 stands for, from the settings and the scene's extent, and that rule
  // in words ("the scene's extent / 6").
  float (*derive)(const RenderSettings&, const SceneSize&) = nullptr;
  std::string_view autoRule;

  // Its history column, or the path's own registerHistoryInputs, names `path`.
  bool resetsHistoryOf(std::string_view path) const;
};

// A plugin's setting, declared where the plugin lives (plugins/<name>/), as the engine's are in
// TL_RENDER_SETTINGS: the same columns, the same schema (JSON, `--set`, the editor's panel, the
// reference table, tune). Made from a static object in the plugin's .cpp, before main():
//   const PluginSetting<uint32_t> kRays{"bentSkyRays", 4, 1, 64, "rays", "bentsky", "bentsky",
//                                       kSettingPlain, "sky-visibility rays per pixel and frame"};
//   ... kRays.of(settings) ...
// Registering throws std::logic_error (a message at start-up) when the name is taken, the slots
// (kMaxPluginSettings) are used up, or the schema was already read: never a silent loss.
uint32_t registerPluginSetting(SettingInfo info);  // its slot in RenderSettings::pluginValues

template <class T>
class PluginSetting {
  static_assert(std::is_same_v<T, bool> || std::is_same_v<T, uint32_t> || std::is_same_v<T, float>,
                "a plugin's setting is a switch, a whole number or a number");

 public:
  PluginSetting(std::string_view name, T def, double min, double max, std::string_view unit, std::string_view owner,
                std::string_view history, uint32_t flags, std::string_view help)
      : slot_(registerPluginSetting({name, type(), double(def), min, max, unit, owner, history, flags, help, {}, {}, {}})),
        default_(def) {}

  // The value in `settings` (the default where it was never set), in the setting's type.
  T of(const RenderSettings& settings) const {
    const double v = pluginSettingValue(settings, slot_, double(default_));
    if constexpr (std::is_same_v<T, bool>) return v != 0.0;
    else return T(v);
  }

 private:
  static constexpr SettingType type() {
    if constexpr (std::is_same_v<T, bool>) return SettingType::Bool;
    else if constexpr (std::is_same_v<T, uint32_t>) return SettingType::UInt;
    else return SettingType::Float;
  }
  uint32_t slot_;
  T default_;
};

// A plugin's path whose history also restarts when these engine settings change (the
// materials, the light shadow maps, the ray length it borrows): declared by the plugin, so the
// engine's TL_RENDER_SETTINGS never names a plugin. Each name must be a setting, checked when
// the schema is first read (std::logic_error).
void registerHistoryInputs(std::string_view path, std::vector<std::string_view> settings);
struct HistoryInputsRegistrar {
  HistoryInputsRegistrar(std::string_view path, std::vector<std::string_view> settings) {
    registerHistoryInputs(path, std::move(settings));
  }
};

// Every setting, in declaration order.
const std::vector<SettingInfo>& settingsSchema();
const SettingInfo* findSetting(std::string_view name);

// Why `value` (already in the setting's C++ type: a whole number for an integer, 0/1 for a
// switch, an index for an enum) is not valid for the setting, or nothing when it is.
std::optional<std::string> settingRangeError(const SettingInfo& setting, double value);
// "2048", "true", "0.25", "clay": the value as text (for `--set`, tables and the UI).
std::string formatSetting(const SettingInfo& setting, double value);
// Parses `text` ("true", "2048", "0.5", "clay") into the setting's stored value, then checks
// the range; throws std::invalid_argument with what the setting takes.
double parseSetting(const SettingInfo& setting, std::string_view text);
// What the setting takes, in words: "a whole number in [256, 8192], a power of two".
std::string settingDomain(const SettingInfo& setting);

// The hash of the settings whose `history` column names `path` (0 when none does): the frame
// key's settings part for that path, so changing one of them restarts its history.
uint64_t historySettingsHash(const RenderSettings& settings, std::string_view path);

// Automatic values. A kSettingAuto setting at 0 stands for a value derived from the scene's
// extent (`sceneScale`: the diagonal of its bounds, in the scene's own units) or the image,
// never a length in metres: a scene authored in millimetres or kilometres gets the same
// picture. The derivations are the schema's (render_settings.cpp, one table; each setting's
// `autoRule` says it in words); a value the user sets keeps meaning metres.
// The value a kSettingAuto setting stands for at 0 (nothing for another setting).
std::optional<float> autoSettingValue(const SettingInfo& setting, const RenderSettings& settings, const SceneSize& scene);
std::optional<float> autoSettingValue(std::string_view name, const RenderSettings& settings, const SceneSize& scene);
// The settings a frame renders with: every automatic setting left at 0 replaced by its value.
RenderSettings resolveAutomatic(const RenderSettings& settings, const SceneSize& scene);

}  // namespace tl::lighting
