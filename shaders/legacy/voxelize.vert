#version 460
// Voxelization: each triangle is rasterised orthographically along one axis into an R x R
// viewport covering one clipmap level; the fragment shader writes the voxel it lands in.
// Three passes (x, y, z) per level catch surfaces at any orientation. A partial update draws
// only the instances near its region, with a scissor around it (legacy_path.cpp).
//
// The vertices are fetched here, a whole triangle per invocation (an unindexed draw:
// gl_VertexIndex is the position in the index buffer), so that a triangle which cannot
// produce a fragment in this projection is dropped before the rasterizer sets it up: one
// whose bounding box holds no pixel centre, or which lies outside the region along the
// projection axis. Fine meshes (a cloth of triangles smaller than a voxel) mostly produce
// none in two of the three projections; the voxels come out exactly as with every triangle
// drawn, at a fraction of the triangle set-ups.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame.h"
#include "shared/legacy.h"
#include "shared/scene.h"

layout(set = 0, binding = kLegacyBindingFrame) uniform Frame { FrameConstants frame; };
layout(set = 0, binding = kLegacyBindingVertices, std430) readonly buffer Vertices { float vertexData[]; };
layout(set = 0, binding = kLegacyBindingIndices, std430) readonly buffer Indices { uint indexData[]; };
layout(set = kSceneSet, binding = kSceneBindingInstances, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { LegacyVoxelPush push; };

layout(location = 0) out vec3 outPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) flat out uint outInstance;
layout(location = 4) out vec2 outUv1;
layout(location = 5) out vec4 outColor;

vec3 vertexVec3(uint vertex, uint at) {
  uint b = vertex * kVertexFloats + at;
  return vec3(vertexData[b], vertexData[b + 1u], vertexData[b + 2u]);
}

// A point in this projection: xy in pixels of the R x R raster, z in voxels along the axis.
vec3 projected(vec3 world, uint axis, vec4 box) {
  vec3 t = (world - box.xyz) / box.w;
  return axis == 0u ? t.yzx : (axis == 1u ? t.zxy : t.xyz);
}

// Whether the triangle can write a voxel of the region here: a pixel centre inside its
// bounding box and the scissor, and a depth range meeting the region's. The margin covers
// the rasterizer's sub-pixel snapping; it only ever keeps a triangle that makes nothing.
bool mayWrite(vec3 a, vec3 b, vec3 c, uint axis) {
  const float margin = 1.0 / 64.0;
  vec3 lo = min(a, min(b, c)) - margin, hi = max(a, max(b, c)) + margin;
  ivec3 rmin = axis == 0u ? push.regionMin.yzx : (axis == 1u ? push.regionMin.zxy : push.regionMin.xyz);
  ivec3 rmax = axis == 0u ? push.regionMax.yzx : (axis == 1u ? push.regionMax.zxy : push.regionMax.xyz);
  // Pixel centres p + 0.5 within [lo, hi], p in [rmin, rmax).
  vec2 first = max(ceil(lo.xy - 0.5), vec2(rmin.xy)), last = min(floor(hi.xy - 0.5), vec2(rmax.xy - 1));
  if (any(greaterThan(first, last))) return false;
  // Fragments land in voxel floor(z): some must fall in [rmin.z, rmax.z).
  return hi.z >= float(rmin.z) && lo.z < float(rmax.z);
}

void main() {
  GpuInstance inst = instances[gl_InstanceIndex];
  uint axis = push.axis % 3u, level = push.axis / 3u;
  vec4 box = push.clipmap.levelMin[level];
  uint corner = uint(gl_VertexIndex) % 3u, first = uint(gl_VertexIndex) - corner;  // meshes start on whole triangles
  vec3 p[3];
  for (uint k = 0u; k < 3u; ++k)
    p[k] = projected(vec3(inst.modelRelative * vec4(vertexVec3(indexData[first + k] + inst.vertexOffset, 0u), 1.0)), axis, box);
  uint vertex = indexData[uint(gl_VertexIndex)] + inst.vertexOffset;
  vec3 world = vec3(inst.modelRelative * vec4(vertexVec3(vertex, 0u), 1.0));
  if (mayWrite(p[0], p[1], p[2], axis)) {
    vec3 t = (world - box.xyz) / (box.w * float(push.clipmap.resolution));  // [0,1] inside the level
    vec3 swizzled = axis == 0u ? t.yzx : (axis == 1u ? t.zxy : t.xyz);
    gl_Position = vec4(swizzled.xy * 2.0 - 1.0, clamp(swizzled.z, 0.0, 1.0), 1.0);
  } else {
    gl_Position = vec4(-2.0, -2.0, 0.5, 1.0);  // all three corners outside the same clip plane: rejected
  }
  outPosition = world;
  outNormal = mat3(inst.normalMatrix) * vertexVec3(vertex, kVertexNormal);
  uint at = vertex * kVertexFloats;
  outUv = vec2(vertexData[at + kVertexUv], vertexData[at + kVertexUv + 1u]);
  outUv1 = vec2(vertexData[at + kVertexUv1], vertexData[at + kVertexUv1 + 1u]);
  outColor = vec4(vertexData[at + kVertexColor], vertexData[at + kVertexColor + 1u], vertexData[at + kVertexColor + 2u],
                  vertexData[at + kVertexColor + 3u]);
  outInstance = uint(gl_InstanceIndex);
}
