#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "shared/reference.h"

layout(location = 1) rayPayloadInEXT RefShadowRay shadowRay;
void main() { shadowRay.reached = 1.0; }
