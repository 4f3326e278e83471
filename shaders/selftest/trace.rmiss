#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "shared/selftest.h"

layout(location = 0) rayPayloadInEXT float hitDistance;
void main() { hitDistance = kSelfTestMiss; }
