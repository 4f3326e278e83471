#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "shared/rt.h"

layout(location = 0) rayPayloadInEXT uint hitRecord;
void main() { hitRecord = kRtHitMiss; }
