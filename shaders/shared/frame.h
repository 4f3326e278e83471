// Per-frame constants shared by every pass (a uniform buffer, the graph's imported
// resource "frame.constants"). All positions are camera-relative: the camera sits at the
// origin of the space the GPU sees, see shared/scene.h GpuInstance.
#ifndef TL_SHARED_FRAME_H
#define TL_SHARED_FRAME_H
#include "common.h"
#include "environment.h"
#include "material_mode.h"

TL_BEGIN
struct FrameConstants {
  mat4 view;             // rotation only: camera-relative world -> view
  mat4 proj;             // infinite reversed-Z perspective or reversed-Z orthographic (cameraAxis.w), Vulkan clip space (y down)
  mat4 viewProj;
  mat4 invViewProj;      // clip -> camera-relative world
  mat4 prevViewProj;     // previous frame's, applied to this frame's camera-relative space
  mat4 sunViewProj;      // camera-relative world -> shadow map clip (orthographic, z in [0,1])
  vec4 sunToLight;       // xyz: unit direction towards the sun, w: angular radius (radians)
  vec4 sunIrradiance;    // rgb: irradiance E on a surface facing the sun
  vec4 skyRadiance;      // rgb: uniform sky radiance L
  vec4 viewport;         // width, height, 1/width, 1/height
  vec4 shadowParams;     // x: texel size (world m), y: depth bias (world m), z: normal offset (texels), w: map size
  vec4 shadowSoftness;   // x: metres per unit of shadow-map depth, y: largest PCSS filter radius (texels), z: 1 = PCSS on
  float exposure;        // multiplier applied before tonemapping: 2^-EV (shared/color.h tlExposureScale)
  uint frameIndex;
  uint flags;            // kFrameFlag*
  float sceneScale;      // characteristic scene size in metres (bounds diagonal)
  vec4 jitter;           // xy: this frame's TAA offset of the projection, in NDC (0 without TAA); viewProj
                         // includes it, prevViewProj does not: motion vectors subtract it
  uint lightCount;       // entries of the light table (shared/lights.h): point, spot, further directional lights
  uint envWidth;         // the environment map's texels (kFrameFlagEnvironment; shared/environment.h)
  uint envHeight;
  uint envPad0;
  vec4 envParams;        // x, y: cosine and sine of the map's rotation about +Y; z: its intensity
  vec4 envSh[9];         // rgb: the map's radiance on the SH basis (rotation and intensity applied)
  vec4 cameraAxis;       // xyz: the unit view direction (camera-relative world); w: 1 orthographic, 0 perspective
  vec4 sceneMin;         // xyz: the scene's bounds (every instance, every animated pose), camera-relative
  vec4 sceneMax;
};

TL_CONST uint kFrameFlagSunShadows = 1u;
// TAA averages frames: stochastic transparency's dither moves each frame (shared/sampling.h).
TL_CONST uint kFrameFlagFramesAveraged = 16u;
// The path is a debug view (PathCapabilities::debugView): its image holds values shown as they
// are, 0..1 as black to white, without exposure or the tonemap curve.
TL_CONST uint kFrameFlagShowValues = 32u;
// Bits 1-2: the material override mode (shared/material_mode.h kMaterials*).
TL_CONST uint kFrameMaterialsShift = 1u;
TL_FN uint tlFrameMaterials(uint flags) { return (flags >> kFrameMaterialsShift) & 3u; }

// Set-0 binding of the frame constants in every pass that reads them.
TL_CONST uint kBindingFrame = 0;

// The sky a surface sees without a path's GI, or a ray that escapes: the environment map's
// band-limited radiance along unit direction d (shared/environment.h) or the uniform sky; the
// irradiance on an unoccluded surface of unit normal n (pi L for the uniform sky).
TL_FN vec3 tlSkyRadiance(FrameConstants f, vec3 d) {
  return (f.flags & kFrameFlagEnvironment) != 0u ? tlEnvShRadiance(f.envSh, d) : vec3(f.skyRadiance);
}
TL_FN vec3 tlSkyIrradiance(FrameConstants f, vec3 n) {
  return (f.flags & kFrameFlagEnvironment) != 0u ? tlEnvShIrradiance(f.envSh, n) : kPi * vec3(f.skyRadiance);
}

// Where a ray from `origin` (inside the scene's bounds) along unit `d` leaves them: past this
// distance there is nothing to meet. A ray shorter than that which meets nothing has not left
// the scene: it ended at its length (RtPush::tMax), and what lies beyond it is unknown.
TL_FN float tlSceneExitDistance(FrameConstants f, vec3 origin, vec3 d) {
  // An axis the ray runs along never limits it (a huge 1/d there, never 0 * inf).
  vec3 safe = vec3(abs(d.x) > 1e-30f ? d.x : 1e-30f, abs(d.y) > 1e-30f ? d.y : 1e-30f, abs(d.z) > 1e-30f ? d.z : 1e-30f);
  vec3 inv = vec3(1.0f) / safe;
  vec3 t0 = (vec3(f.sceneMin) - origin) * inv, t1 = (vec3(f.sceneMax) - origin) * inv;
  vec3 far = max(t0, t1);
  return max(min(far.x, min(far.y, far.z)), 0.0f);
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::FrameConstants) % 16 == 0);
#endif
#endif
