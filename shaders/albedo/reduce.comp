#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/albedo.h"

// Sums one tile per workgroup: each thread walks the tile in a fixed stride, then a tree
// in shared memory. The order never changes, so a bake is repeatable bit for bit.
layout(local_size_x = kAlbedoReduceThreads) in;
layout(binding = kAlbedoBindingAtlas, rgba32f) uniform readonly image2D atlas;
layout(binding = kAlbedoBindingSums, std430) writeonly buffer Sums { AlbedoTileSum sums[]; };
layout(push_constant) uniform Params { AlbedoReduceParams params; };

shared vec4 partial[kAlbedoReduceThreads];

void main() {
  const uint tile = gl_WorkGroupID.x;
  const uint size = params.tileSize;
  const ivec2 origin = ivec2(tile % kAlbedoAtlasTiles, tile / kAlbedoAtlasTiles) * int(size);
  vec4 sum = vec4(0.0);
  for (uint i = gl_LocalInvocationIndex; i < size * size; i += kAlbedoReduceThreads) {
    vec4 texel = imageLoad(atlas, origin + ivec2(i % size, i / size));
    sum += vec4(texel.rgb * texel.a, texel.a);
  }
  partial[gl_LocalInvocationIndex] = sum;
  barrier();
  for (uint stride = kAlbedoReduceThreads / 2; stride > 0; stride /= 2) {
    if (gl_LocalInvocationIndex < stride) partial[gl_LocalInvocationIndex] += partial[gl_LocalInvocationIndex + stride];
    barrier();
  }
  if (gl_LocalInvocationIndex == 0) sums[tile].sum = partial[0];
}
