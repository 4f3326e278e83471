#version 460
// Rooms, one flood step (shared/legacy.h): each invocation walks one line of the finest level
// along push.axis, forwards and back, and marks every empty voxel of a run of empty voxels
// that holds a reached one as reached. Sweeps along x, y and z in turn reach any empty voxel
// joined to a reached one by a path of as many straight runs; lines are independent, so a
// sweep writes each voxel from one invocation. A round that reaches no voxel is a fixed point:
// the last round's sweeps (push.level 1) count what they reach, so the cones know whether the
// flood settled.
#extension GL_GOOGLE_include_directive : require
#include "shared/legacy.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingReach, r8ui) uniform uimage3D reach;
layout(set = 0, binding = kLegacyBindingReachUnsettled, std430) buffer Unsettled { uint unsettledVoxels; };
layout(push_constant) uniform Push { LegacyVoxelPush push; };

ivec3 onLine(ivec2 line, int i) {
  return push.axis == 0u ? ivec3(i, line) : (push.axis == 1u ? ivec3(line.y, i, line.x) : ivec3(line, i));
}

void main() {
  int R = int(push.clipmap.resolution);
  ivec2 line = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(line, ivec2(R)))) return;
  uint reached = 0u;
  for (int pass = 0; pass < 2; ++pass) {  // forwards, then back
    bool lit = false;
    for (int k = 0; k < R; ++k) {
      ivec3 v = onLine(line, pass == 0 ? k : R - 1 - k);
      uint r = imageLoad(reach, v).r;
      if (r == kLegacyReachSolid)
        lit = false;
      else if (r == kLegacyReachLit)
        lit = true;
      else if (lit)
        imageStore(reach, v, uvec4(kLegacyReachLit)), ++reached;
    }
  }
  if (push.level != 0u && reached > 0u) atomicAdd(unsettledVoxels, reached);
}
