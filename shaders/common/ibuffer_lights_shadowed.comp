#version 460
// lights.direct in redeferred form (the I-buffer's sums of light, shared/redeferred.h) with
// shadow maps (the direct and legacy paths): point and spot lights with a map
// (shadow.lightsDepth) are hidden where it holds a caster, as in lights_shadowed.comp.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/sampling.h"
#include "shared/redeferred.h"
#include "shared/shading.h"

vec3 gShadowOrigin;  // unused: no shadow rays
float lightVisibility(uint light, vec3 toLight, float distance);

#include "common/ibuffer_lights.glsl"
#define TL_AREA_SHADOW_PER_FRAME  // lights.direct accumulates sampled area shadows
#include "common/light_shadow.glsl"

float lightVisibility(uint light, vec3 toLight, float distance) { return lightShadowVisibility(light, gPosition, gNormalHere); }
