#version 460
// Empties one region of one clipmap level in all six face blocks before a partial update
// re-voxelizes it (a transfer clear can only empty the whole image). One invocation per
// voxel of the region and face: x runs over the six faces' copies of the region side by side.
#extension GL_GOOGLE_include_directive : require
#include "shared/legacy.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = kLegacyBindingRadiance, rgba16f) uniform writeonly image3D radianceOut;
layout(push_constant) uniform Push { LegacyVoxelPush push; };

void main() {
  ivec3 g = ivec3(gl_GlobalInvocationID);
  ivec3 size = push.regionMax.xyz - push.regionMin.xyz;
  if (g.x >= 6 * size.x || any(greaterThanEqual(g.yz, size.yz))) return;
  int R = int(push.clipmap.resolution);
  int face = g.x / size.x;
  ivec3 v = push.regionMin.xyz + ivec3(g.x - face * size.x, g.y, g.z);
  imageStore(radianceOut, ivec3(v.x + face * R, v.y, v.z + int(push.level) * R), vec4(0.0));
}
