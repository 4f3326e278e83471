#version 460
#extension GL_GOOGLE_include_directive : require
#include "common/display_uint.glsl"
