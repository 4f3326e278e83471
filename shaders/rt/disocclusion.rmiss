#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "shared/rt.h"

layout(location = 0) rayPayloadInEXT uvec3 hitPayload;
void main() { hitPayload = uvec3(kRtHitMiss, 0u, 0u); }
