#version 460
// One mip of the anisotropic voxel clipmap, over one region of one level (a full rebuild's
// region is the whole level; a partial update's, the footprint of what it re-voxelized). For
// the face block pointing along +a (or -a), the two children along a are composited front to
// back as seen from that side (premultiplied radiance rgb, opacity a), then the four such
// pairs are averaged: a thin wall perpendicular to a stays opaque at every level, and a cone
// sees what lies nearest to it first (VXGI's anisotropic voxels). Levels and face blocks are
// powers of two in size, so children never straddle two blocks, and the children of texel d
// sit at 2d + o in the source whatever the face or level.
#extension GL_GOOGLE_include_directive : require
#include "shared/legacy.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = kLegacyBindingMipSrcRadiance, rgba16f) uniform readonly image3D src;
layout(set = 0, binding = kLegacyBindingRadianceMips, rgba16f) uniform writeonly image3D dst;
layout(push_constant) uniform Push { LegacyVoxelPush push; };

void main() {
  ivec3 g = ivec3(gl_GlobalInvocationID);
  ivec3 size = push.regionMax.xyz - push.regionMin.xyz;  // in this mip's texels of one level and face
  if (g.x >= 6 * size.x || any(greaterThanEqual(g.yz, size.yz))) return;
  int side = imageSize(dst).y;  // one level's (and one face block's) side at this mip
  int face = g.x / size.x;
  ivec3 d = push.regionMin.xyz + ivec3(g.x - face * size.x, g.y, g.z) + ivec3(face * side, 0, int(push.level) * side);
  int axis = face / 2;
  int front = (face & 1) == 0 ? 1 : 0;  // +a faces are seen from the +a side: the larger child first
  vec4 sum = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    int u = i & 1, v = i >> 1;
    ivec3 o = axis == 0 ? ivec3(0, u, v) : (axis == 1 ? ivec3(u, 0, v) : ivec3(u, v, 0));
    ivec3 nearChild = 2 * d + o, farChild = 2 * d + o;
    nearChild[axis] += front;
    farChild[axis] += 1 - front;
    vec4 a = imageLoad(src, nearChild), b = imageLoad(src, farChild);
    sum += a + (1.0 - a.a) * b;
  }
  imageStore(dst, d, sum * 0.25);
}
