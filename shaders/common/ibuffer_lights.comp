#version 460
// lights.direct in redeferred form (the I-buffer's sums of light, shared/redeferred.h) without
// shadows (the direct and legacy paths): every light reaches every point that faces it.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/sampling.h"
#include "shared/redeferred.h"
#include "shared/shading.h"

vec3 gShadowOrigin;  // unused: no shadow rays
float lightVisibility(uint light, vec3 toLight, float distance) { return 1.0; }

#include "common/ibuffer_lights.glsl"
