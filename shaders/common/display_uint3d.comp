#version 460
#extension GL_GOOGLE_include_directive : require
#define DISPLAY_3D 1
#include "common/display_uint.glsl"
