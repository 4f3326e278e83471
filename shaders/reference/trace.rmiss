#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_tracing : require
#include "shared/reference.h"

layout(location = 0) rayPayloadInEXT RefHit hit;
void main() { hit.positionT.w = -1.0; }
