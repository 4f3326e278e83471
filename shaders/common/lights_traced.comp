#version 460
// lights.direct with ray-traced shadows (the rt path): one ray query per light towards it,
// against the path's top level, stopping just short of a point light.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/packing.h"
#include "shared/ray_origin.h"
#include "shared/sampling.h"
#include "shared/shading.h"

layout(set = 0, binding = kLightsPassTlas) uniform accelerationStructureEXT tlas;
#define TL_LIGHTS_AREA TL_AREA_ANALYTIC_TRACED  // area lights: unshadowed light times shadow rays (common/lights.glsl)
vec3 gShadowOrigin;

float lightVisibility(uint light, vec3 toLight, float distance) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xFF, gShadowOrigin, 0.0,
                        toLight, distance * (1.0 - 1e-4));
  while (rayQueryProceedEXT(q)) {}
  return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionNoneEXT ? 1.0 : 0.0;
}

#include "common/lights_shade.glsl"
