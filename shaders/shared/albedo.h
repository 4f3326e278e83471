// The albedo baker (engine/albedo/albedo_baker.cpp, shaders/albedo/): each mesh + material
// combination is drawn from 6 orthographic directions into its own tiles of one atlas; a
// reduction sums every tile. Shared by C++ and GLSL.
#ifndef TL_SHARED_ALBEDO_H
#define TL_SHARED_ALBEDO_H
#include "common.h"

TL_BEGIN
TL_CONST uint kAlbedoAtlasTiles = 16;      // tiles per atlas side: 256 tiles, 42 combinations a batch
TL_CONST uint kAlbedoReduceThreads = 256;  // one workgroup per tile

TL_CONST uint kAlbedoBindingAtlas = 0;  // reduce: the atlas (storage image, rgba32f)
TL_CONST uint kAlbedoBindingSums = 1;   // reduce: AlbedoTileSum per tile

// Push constants of one tile's draw.
struct AlbedoBakeDraw {
  mat4 objectToClip;  // orthographic view of the mesh's bounds, depth reversed (1 = nearest); the tile is the viewport
  uint material;
  uint pad0;
  uint pad1;
  uint pad2;
};

struct AlbedoReduceParams {
  uint tileSize;   // pixels per tile side
  uint tileCount;  // tiles drawn this batch
  uint pad0;
  uint pad1;
};

// One tile's sums: rgb of the hit albedo over its covered pixels, w the covered pixel count.
struct AlbedoTileSum {
  vec4 sum;
};

// Debug views of the resolved albedo (lighting/common/albedo_view_pass.cpp).
TL_CONST uint kAlbedoViewBindingInstanceId = 0;  // gbuffer.instanceId
TL_CONST uint kAlbedoViewBindingBaseColor = 1;   // gbuffer.baseColor
TL_CONST uint kAlbedoViewBindingMaterial = 2;    // gbuffer.material
TL_CONST uint kAlbedoViewBindingPerInstance = 3; // vec4 per instance: rgb resolved albedo, w source
TL_CONST uint kAlbedoViewBindingInstance = 4;    // out: albedo.instance
TL_CONST uint kAlbedoViewBindingDifference = 5;  // out: albedo.difference
TL_CONST uint kAlbedoViewBindingCurrent = 6;     // impact: composite.hdr
TL_CONST uint kAlbedoViewBindingBaseline = 7;    // impact: the image before the edits
TL_CONST uint kAlbedoViewBindingImpact = 8;      // out: albedo.impact

// Source codes in albedo.instance's alpha (0: no surface).
TL_CONST float kAlbedoSourceOverride = 1.0f;
TL_CONST float kAlbedoSourceBaked = 2.0f;
TL_CONST float kAlbedoSourceTextureAverage = 3.0f;
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::AlbedoBakeDraw) == 80);
#endif
#endif
