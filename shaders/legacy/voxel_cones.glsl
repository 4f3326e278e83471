// Cone tracing through the legacy path's voxel clipmap (shared/legacy.h), shared by the diffuse
// cones (cones.comp) and the specular cone (reflections.comp): a face-weighted sample of the
// anisotropic voxels at a cone's diameter, and whether light reaches the air a cone starts in.
// The includer declares `push` with the clipmap (push.clipmap) before including this file.
#ifndef TL_LEGACY_VOXEL_CONES_GLSL
#define TL_LEGACY_VOXEL_CONES_GLSL
layout(set = 0, binding = kLegacyBindingRadiance) uniform sampler3D radiance0;
layout(set = 0, binding = kLegacyBindingRadianceMips) uniform sampler3D radianceMips;
layout(set = 0, binding = kLegacyBindingReach) uniform usampler3D reach;  // rooms (shared/legacy.h), when roomGate
layout(set = 0, binding = kLegacyBindingReachUnsettled, std430) readonly buffer Unsettled { uint unsettledVoxels; };


struct VoxelSample {
  vec3 radiance;  // premultiplied by coverage
  float opacity;
};

// The faces that look back along -dir (towards the cone's apex), weighted by dir's squared
// components: premultiplied radiance (rgb) and opacity (a). Axes with under 10% of the weight
// (more than 72 degrees from the cone) are left out: each face is a trilinear tap across two
// mips, the cones' whole cost on lavapipe, and those faces barely change the image (see
// docs/performance.md, legacy section).
const float kMinFaceWeight = 0.1;
vec4 facesTowards(vec3 dir, vec3 uvw, float lod, bool mip, uint level, uint levels) {
  vec3 w = dir * dir;
  vec4 sum = vec4(0.0);
  for (int a = 0; a < 3; ++a) {
    if (w[a] < kMinFaceWeight) continue;
    int face = 2 * a + (dir[a] > 0.0 ? 1 : 0);
    vec3 t = vec3((float(face) + uvw.x) / 6.0, uvw.y, (float(level) + uvw.z) / float(levels));
    sum += w[a] * (mip ? textureLod(radianceMips, t, lod) : textureLod(radiance0, t, 0.0));
  }
  return sum / (w.x * float(w.x >= kMinFaceWeight) + w.y * float(w.y >= kMinFaceWeight) + w.z * float(w.z >= kMinFaceWeight));
}

VoxelSample sampleClipmap(vec3 position, vec3 dir, float diameter) {
  LegacyClipmap c = push.clipmap;
  float R = float(c.resolution);
  float lodGlobal = max(log2(diameter / c.levelMin[0].w), 0.0);
  uint level = min(uint(lodGlobal), c.levels - 1u);
  // Move out to a level that contains the point.
  for (; level < c.levels; ++level) {
    vec3 uvw = (position - c.levelMin[level].xyz) / (c.levelMin[level].w * R);
    if (all(greaterThan(uvw, vec3(0.0))) && all(lessThan(uvw, vec3(1.0)))) break;
  }
  VoxelSample s;
  s.radiance = vec3(0.0);
  s.opacity = 0.0;
  if (level >= c.levels) return s;  // outside the clipmap: empty (the sky)
  vec3 uvw = (position - c.levelMin[level].xyz) / (c.levelMin[level].w * R);
  float lod = clamp(lodGlobal - float(level), 0.0, float(c.mipCount));
  // Keep trilinear taps inside this level's block along z and inside the face block along x.
  float texel = exp2(lod) / R;
  uvw = clamp(uvw, vec3(0.5 * texel), vec3(1.0 - 0.5 * texel));
  // Mip 0 lives in its own image: below lod 1 it is read alone (no blend across images).
  vec4 v = lod < 1.0 ? facesTowards(dir, uvw, 0.0, false, level, c.levels)
                     : facesTowards(dir, uvw, lod - 1.0, true, level, c.levels);
  s.radiance = v.rgb;
  s.opacity = v.a;
  return s;
}

// Whether light can reach the air the cones start in: false only where the finest level's
// flood found that air sealed off from every lit surface and from the sky (shared/legacy.h).
// The cones start in an empty voxel, or, near a wall or in a corner, in one a surface's voxels
// hold: then the air around it decides, and light reaches unless all of that air is sealed
// (pockets inside thick walls are sealed too; the other side of a wall at least one voxel thick
// lies beyond the 3x3x3 block of a voxel on its near face).
bool lightReaches(vec3 origin) {
  LegacyClipmap c = push.clipmap;
  if (c.roomGate == 0u || unsettledVoxels != 0u) return true;  // off, or the flood may not have settled
  ivec3 v = ivec3(floor((origin - c.levelMin[0].xyz) / c.levelMin[0].w));
  int R = int(c.resolution);
  if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(R)))) return true;  // outside: the cones decide
  uint here = texelFetch(reach, v, 0).r;
  if (here != kLegacyReachSolid) return here == kLegacyReachLit;
  bool air = false;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 u = clamp(v + ivec3(dx, dy, dz), ivec3(0), ivec3(R - 1));
        uint r = texelFetch(reach, u, 0).r;
        if (r == kLegacyReachLit) return true;
        air = air || r == kLegacyReachSealed;
      }
  return !air;  // no air around: nothing is known, the cones decide
}

// A cone from `origin` (a surface point lifted off its voxel along the normal `n`) along `dir`,
// front to back through the voxels' opacity, until `range` or an opacity of `stopAt`: the
// radiance gathered and the occlusion reached, and the occlusion reached within `nearRange`
// (the voxel AO's radius).
struct ConeMarch {
  vec3 gathered;
  float occlusion;
  float nearOcclusion;
};
ConeMarch marchCone(vec3 origin, vec3 n, vec3 dir, float tanHalfAperture, float range, float stopAt, float nearRange) {
  float voxel = push.clipmap.levelMin[0].w;
  ConeMarch m;
  m.gathered = vec3(0.0);
  m.occlusion = 0.0;
  m.nearOcclusion = 0.0;
  float t = voxel;
  while (t < range && m.occlusion < stopAt) {
    float diameter = max(2.0 * t * tanHalfAperture, voxel);
    // Samples keep 1.5 times their own size off the surface: a coarse voxel holding the
    // surface would otherwise occlude the cone with the surface it starts from (the
    // surface may lie anywhere in its voxel, and trilinear taps reach one voxel further).
    VoxelSample s = sampleClipmap(origin + dir * t + n * (1.5 * diameter), dir, diameter);
    // Opacity is per voxel-sized step: correct it for the actual step length.
    float stepLength = diameter * push.coneStep;
    float a = 1.0 - pow(max(1.0 - s.opacity, 0.0), stepLength / diameter);
    m.gathered += (1.0 - m.occlusion) * s.radiance * (a / max(s.opacity, 1e-4));
    m.occlusion += (1.0 - m.occlusion) * a;
    if (t < nearRange) m.nearOcclusion = m.occlusion;
    t += stepLength;
  }
  return m;
}
#endif
