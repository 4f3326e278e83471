// The ray-traced path's settings: its acceleration structures, rays, pre-trace, accumulation,
// denoiser, radiance cache, reflections, sampling, culling, refits and hybrid sun shadows.
// One line per setting, the columns of TL_RENDER_SETTINGS (render_settings.h), which gathers
// this group and names its owner: `owner` below is that name, so no line restates it.
// A new setting of this group is one line here.
#pragma once

// clang-format off
#define TL_RT_SETTINGS(X, owner) \
  X(float, rtSimplifyRatio, 0.25f, 0.01f, 1.0f, "x", owner, "rt", kSettingTune, "RT (BLAS) mesh triangles / source triangles (Metro: about 4x fewer); 1 = the full mesh") \
  X(float, rtSimplifyError, 0.01f, 0.0f, 1.0f, "x size", owner, "rt", kSettingPlain, "largest deviation the simplifier may introduce, as a fraction of the mesh's size") \
  X(float, rtAoRadius, 0.0f, 0.0f, 1e9f, "m", owner, "rt reference", kSettingAuto, "RTAO radius: a hit closer than this occludes (also the reference's AO)") \
  X(float, rtRayLength, 0.0f, 0.0f, 1e9f, "m", owner, "rt", kSettingAuto, "GI rays stop after this distance; also the top level's culling margin") \
  X(float, rtBlendDistance, 0.0f, 0.0f, 1e9f, "m", owner, "rt", kSettingAuto, "beyond this view distance RT GI fades to the far field (Metro: 250 m); the top level culls instances beyond it") \
  X(bool, rtFarLegacy, true, 0, 1, "", owner, "", kSettingPlain, "the far field beyond the blend distance is the legacy path's voxel GI (Metro), else the unoccluded sky") \
  X(bool, rtPretrace, true, 0, 1, "", owner, "rt", kSettingTune | kSettingFeature, "screen-space pre-trace: march the depth buffer first, real rays only where it finds nothing") \
  X(uint32_t, rtPretraceSteps, 16, 1, 256, "steps", owner, "rt", kSettingTune, "depth samples along a pre-traced ray") \
  X(float, rtPretracePixels, 0.0f, 0.0f, 16384.0f, "px", owner, "rt", kSettingAuto, "screen length of a pre-traced ray (auto: 128 px per 360 lines of the image)") \
  X(float, rtThickness, 0.02f, 0.0f, 1.0f, "x distance", owner, "rt", kSettingPlain, "assumed thickness of what the depth buffer shows, as a fraction of its view distance") \
  X(bool, rtHalfRays, false, 0, 1, "", owner, "", kSettingTune, "0.5 rays per pixel: a checkerboard that alternates each frame; the other half borrows a neighbour's ray") \
  X(bool, rtHalfResolution, false, 0, 1, "", owner, "", kSettingTune, "0.25 rays per pixel: one pixel of each 2x2, cycling, depth-aware noisy upsampling (INSIDE); wins over rtHalfRays") \
  X(bool, rtTwoRays, false, 0, 1, "", owner, "", kSettingTune, "2 rays per traced pixel (pre-trace, trace and hit lighting run twice; twice the cost, half the variance)") \
  X(uint32_t, rtMaxAccumFrames, 32, 1, 1024, "frames", owner, "", kSettingPlain, "temporal accumulation window while the camera holds still") \
  X(float, rtFireflyClamp, 0.0f, 0.0f, 1e6f, "x RMS", owner, "rt", kSettingPlain, "a sample's luma above this multiple of its neighbourhood's / history's RMS is clipped, in linear space (0: off)") \
  X(bool, rtLumaRejection, true, 0, 1, "", owner, "", kSettingPlain, "when the light changes, clip each pixel's history to this frame's samples around it (no ghosting; RE ENGINE)") \
  X(uint32_t, rtDisocclusionRays, 0, 0, 64, "rays", owner, "", kSettingTune, "rays per 8x8 cell holding a pixel whose history was rejected (RE ENGINE; 0: off)") \
  X(bool, rtDenoise, true, 0, 1, "", owner, "", kSettingTune | kSettingFeature, "two-pass spatial denoiser on the SH after accumulation (Metro's)") \
  X(float, rtDenoiseRadius, 0.0f, 0.0f, 1e9f, "m", owner, "", kSettingAuto, "denoiser pass 1 base radius; pass 2 uses half (Metro: 6 m and 3 m)") \
  X(bool, rtScreenRadiance, true, 0, 1, "", owner, "rt", kSettingTune | kSettingFeature, "hits seen on screen last frame reuse its shaded radiance, so light bounces more than once") \
  X(bool, rtHitSky, true, 0, 1, "", owner, "rt", kSettingTune | kSettingFeature, "hits lit afresh (off screen) also see the sky, through one more ray") \
  X(float, rtCacheMinGain, 0.02f, 0.0f, 2.0f, "share", owner, "", kSettingTune | kSettingFeature | kSettingOffAtMax, "radiance cache: runs while the light it adds (bounces off surfaces off screen) is at least this share of the bounced light, measured every frame; stops below half of it (0: always; above 1: never)") \
  X(uint32_t, rtCachePaths, 4096, 16, 1u << 20, "paths", owner, "", kSettingTune, "radiance cache: update paths a frame, at least (one pixel of each square tile that gives this many starts one)") \
  X(uint32_t, rtCacheBounces, 8, 1, 8, "rays", owner, "", kSettingTune, "radiance cache: rays of an update path at most; from the third on a path goes on with the probability of its surface's albedo (Russian roulette), and where it ends it reads the cache, so light bounces on from frame to frame") \
  X(uint32_t, rtCacheMaxSamples, 64, 1, 65536, "samples", owner, "", kSettingPlain, "radiance cache: a cell averages at most this many samples (fewer: follows changes sooner, noisier)") \
  X(float, rtCacheCellAngle, 0.03f, 0.001f, 1.0f, "rad", owner, "", kSettingPlain, "radiance cache: a cell is at least this angle times its distance from the camera across") \
  X(float, rtCacheCellSize, 0.0f, 0.0f, 1e9f, "m", owner, "", kSettingAuto, "radiance cache: the smallest cell (auto: the scene's size / 1000)") \
  X(uint32_t, rtCacheEntries, 1u << 16, 1u << 10, 1u << 24, "cells", owner, "", kSettingPow2, "radiance cache: hash table slots (32 + 48 bytes each)") \
  X(float, rtReflectionRoughness, 0.5f, 0.0f, 1.0f, "roughness", owner, "", kSettingTune | kSettingFeature | kSettingReflections, "reflections: pixels below this roughness trace one specular ray a frame (GGX visible normals), blended into the SH specular over the top fifth of the range; 0: no traced reflections, the SH specular everywhere") \
  X(float, rtMirrorRoughness, 0.02f, 0.0f, 1.0f, "roughness", owner, "", kSettingReflections, "reflections: at or below this roughness the ray is the perfect reflection and the image is not filtered across pixels (RE ENGINE's mirrors)") \
  X(uint32_t, rtReflectionFrames, 16, 1, 1024, "frames", owner, "", kSettingReflections, "reflections: temporal accumulation window (reprojected by the reflected point's virtual position)") \
  X(float, rtReflectionClamp, 1.5f, 0.1f, 100.0f, "sigma", owner, "", kSettingReflections, "reflections: the history is clamped to this many standard deviations around this frame's 3x3 neighbourhood (what moved in a mirror leaves no ghost; larger: less noise, longer ghosts)") \
  X(float, rtReflectionFilterRadius, 8.0f, 0.0f, 64.0f, "px", owner, "", kSettingReflections, "reflections: the spatial filter's largest radius (its footprint follows hit distance x roughness)") \
  X(uint32_t, rtReflectionRoughDivisor, 1, 1, 2, "", owner, "", kSettingPow2 | kSettingTune | kSettingReflections, "reflections: rays for pixels above the mirror threshold, 1 every frame, 2 on a checkerboard flipped each frame (the temporal pass fills the others from their history and traced neighbours); mirrors trace every frame") \
  X(bool, rtEnvironmentSampling, true, 0, 1, "", owner, "rt", kSettingTune | kSettingFeature, "with an environment map, each traced pixel also takes a shadow ray towards a direction drawn by the map's importance, weighed against its GI ray by MIS: the pixel sees the map's texels, not its order-2 SH") \
  X(bool, rtEmitterSampling, true, 0, 1, "", owner, "rt", kSettingTune | kSettingFeature, "emissive triangles are sampled at pixels and hits through shadow rays, not found only by chance") \
  X(float, rtCullAngle, 0.002f, 0.0f, 3.14159f, "rad", owner, "rt", kSettingTune, "contribution culling: instances subtending less are left out of the top level") \
  X(float, rtCullMargin, 0.0f, 0.0f, 1e9f, "m", owner, "rt", kSettingAuto, "expanded frustum: margin around the view frustum within which instances stay in the top level (a visible point's ray reaches that far)") \
  X(uint32_t, rtRefitTop, 16, 0, 65536, "meshes", owner, "", kSettingPlain, "deforming meshes whose BLAS is refitted each frame: the highest priorities (Metro: 16)") \
  X(uint32_t, rtRefitRandom, 4, 0, 65536, "meshes", owner, "", kSettingPlain, "plus this many others drawn at random, so none waits forever (Metro: 4)") \
  X(uint32_t, rtRefitVertexBudget, 1u << 20, 0, 1u << 30, "vertices", owner, "", kSettingPlain, "vertices refitted per frame at most (the first pick always goes)") \
  X(bool, hybridShadows, true, 0, 1, "", owner, "", kSettingTune | kSettingFeature, "hybrid ray-traced sun shadows (GameWorks HRTS): a ray's hard shadow near contacts, PCSS further away, blended by blocker distance (shadow.sun.visibility); off: the shadow map alone") \
  X(float, hybridShadowHardTexels, 4.0f, 0.5f, 64.0f, "texels", owner, "", kSettingPlain, "HRTS: penumbrae narrower than this many shadow-map texels take the ray's hard shadow; linear blend up to it") \
  X(bool, rtRawRayProbe, false, 0, 1, "", owner, "", kSettingNoPanel, "benchmark: also trace the same rays with a trivial kernel (rt.rawRays; bench --rays)")
// clang-format on
