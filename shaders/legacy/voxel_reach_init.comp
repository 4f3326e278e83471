#version 460
// Rooms, step one (shared/legacy.h): each voxel of the finest level as solid, empty and
// reached by light (a seed: in front of a directly lit surface; or on the level's outer faces,
// open to the sky or to whatever lies beyond the level), or empty and not reached yet.
#extension GL_GOOGLE_include_directive : require
#include "shared/legacy.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = kLegacyReachInitVoxels, rgba16f) uniform readonly image3D voxels;
layout(set = 0, binding = kLegacyBindingSeeds, r8ui) uniform readonly uimage3D seeds;
layout(set = 0, binding = kLegacyBindingReach, r8ui) uniform writeonly uimage3D reach;
layout(set = 0, binding = kLegacyBindingReachUnsettled, std430) writeonly buffer Unsettled { uint unsettledVoxels; };
layout(push_constant) uniform Push { LegacyVoxelPush push; };

void main() {
  int R = int(push.clipmap.resolution);
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (all(equal(v, ivec3(0)))) unsettledVoxels = 0u;  // the last round's sweeps count into it
  if (any(greaterThanEqual(v, ivec3(R)))) return;
  // Every written voxel is opaque in every face block (voxelize.frag's first round); the +x
  // block of level 0 is the voxels' own coordinates.
  bool solid = imageLoad(voxels, v).a > 0.0;
  bool edge = any(equal(v, ivec3(0))) || any(equal(v, ivec3(R - 1)));
  uint r = solid ? kLegacyReachSolid : ((edge || imageLoad(seeds, v).r != 0u) ? kLegacyReachLit : kLegacyReachSealed);
  imageStore(reach, v, uvec4(r));
}
