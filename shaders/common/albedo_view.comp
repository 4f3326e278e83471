#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/albedo.h"
#include "shared/rt.h"

// Per pixel, the albedo the RT path's rays read for the visible instance (override, baked
// or texture average; the source in alpha) and how far it is from the G-buffer's own hit
// albedo at that pixel (rgb |difference|, alpha the signed luminance difference).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kAlbedoViewBindingInstanceId) uniform usampler2D gInstanceId;
layout(binding = kAlbedoViewBindingBaseColor) uniform sampler2D gBaseColor;
layout(binding = kAlbedoViewBindingMaterial) uniform sampler2D gMaterial;
layout(binding = kAlbedoViewBindingPerInstance, std430) readonly buffer PerInstance { vec4 perInstance[]; };
layout(binding = kAlbedoViewBindingInstance, rgba16f) uniform writeonly image2D instanceOut;
layout(binding = kAlbedoViewBindingDifference, rgba16f) uniform writeonly image2D differenceOut;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(instanceOut)))) return;
  uint id = texelFetch(gInstanceId, p, 0).r;
  if (id == 0u) {
    imageStore(instanceOut, p, vec4(0.0));
    imageStore(differenceOut, p, vec4(0.0));
    return;
  }
  vec4 resolved = perInstance[id - 1u];
  vec3 screen = tlRtHitAlbedoFromMaterial(texelFetch(gBaseColor, p, 0).rgb, texelFetch(gMaterial, p, 0).g);
  vec3 d = resolved.rgb - screen;
  imageStore(instanceOut, p, resolved);
  imageStore(differenceOut, p, vec4(abs(d), dot(d, vec3(0.2126, 0.7152, 0.0722))));
}
