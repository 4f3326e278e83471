// Visibility of a point, spot or area light through its shadow map (shared/lights.h
// GpuShadowView), for the direct and legacy paths. The includer includes shared/lights.h and
// shared/area_lights.h and declares `lights` (the light table, common/lights.glsl) before
// including this.
layout(set = 0, binding = kBindingLightShadowViews, std430) readonly buffer LightShadowViews { GpuShadowView shadowViews[]; };
layout(set = 0, binding = kBindingLightShadowAtlas) uniform sampler2DShadow lightShadowAtlas;
layout(set = 0, binding = kBindingLightShadowDepth) uniform sampler2D lightShadowDepth;

// 3x3 PCF of hardware 2x2 comparisons: punctual lights cast hard shadows (as the traced paths'
// shadow rays give), filtered over a texel or two. The receiver (camera-relative `position`,
// unit `normal`) is pushed along its normal and towards the light by a few texels of the map at
// its distance. 1 for a light without a map.
float punctualShadowVisibility(uint lightIndex, vec3 position, vec3 normal) {
  uint first = lights[lightIndex].shadowView;
  if (first == kNoLightShadow) return 1.0;
  vec3 lightPosition = lights[lightIndex].position.xyz;
  vec3 fromLight = position - lightPosition;
  uint index = first;
  if (shadowViews[first].params.w > 1.0) index += tlCubeFace(fromLight);
  GpuShadowView view = shadowViews[index];
  float distance = length(fromLight);
  vec3 toLight = -fromLight / max(distance, 1e-6);
  // World size of one texel at the receiver (the map's texels grow with depth); pushed along the
  // normal more where the surface is grazed by the light, as the sun's lookup does.
  float texel = view.params.z * distance;
  float cosine = dot(normal, toLight);
  float slope = sqrt(max(1.0 - cosine * cosine, 0.0));
  vec3 shifted = position + normal * (kLightShadowNormalOffsetTexels * texel * max(slope, 0.2));
  vec4 clip = view.viewProj * vec4(shifted, 1.0);
  if (clip.w <= view.params.x) return 1.0;  // behind the near plane: nothing between
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  float depth = tlShadowViewDepth(view.params.x, view.params.y, clip.w - kLightShadowBiasTexels * texel);
  if (depth >= 1.0) return 1.0;  // beyond the far plane: no caster was drawn there
  vec2 atlasTexel = 1.0 / vec2(textureSize(lightShadowAtlas, 0));
  // Taps stay inside the tile (the guard band holds them for the directions this view owns).
  vec2 lo = view.tile.xy + 1.5 * atlasTexel, hi = view.tile.xy + view.tile.zw - 1.5 * atlasTexel;
  vec2 centre = view.tile.xy + clamp(uv, 0.0, 1.0) * view.tile.zw;
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(lightShadowAtlas, vec3(clamp(centre + vec2(x, y) * atlasTexel, lo, hi), depth));
  return sum / 9.0;
}

// ---- Area lights: percentage-closer soft shadows from the centre's cube map ----
// The map is drawn from the shape's centre C. If the blockers between a receiver X and the shape
// lie at a fraction s of the way from the light (Fernando 2005's blocker search gives s), the
// segment from X to the shape's point C + q crosses them at sX + (1 - s)(C + q), which the map
// sees from C along (X - C) + (1/s - 1) q: the filter's taps are the shape's own points, scaled
// by 1/s - 1 (so a disk parallel to the floor gives the floor its true penumbra, R (1/s - 1)
// wide, and a rectangle an oblong one). Every tap is a direction from C, so a filter wider than
// a cube face reads the face that owns each direction (no seams), and each compares against the
// receiver's plane where that direction meets it, so a wide filter over a surface the light
// grazes does not shadow the surface by itself.

#include "common/poisson_disk.glsl"

// The shape's point (from its centre) for the point p of the unit disk: a disk's own, a
// rectangle's as the ellipse of its area, a tube's on the ribbon of its diameter that faces the
// receiver (along `axis`, from the light to it).
vec3 areaShadowShapePoint(GpuLight l, vec2 p, vec3 axis) {
  if (l.type == kLightTube) {
    vec3 across = cross(l.axisU.xyz, axis);
    float len = length(across);
    return p.x * l.axisU.xyz + (len > 1e-6 ? p.y * l.axisU.w / len : 0.0) * across;
  }
  float scale = l.type == kLightRect ? 1.1283792 : 1.0;  // 2 / sqrt(pi)
  return scale * (p.x * l.axisU.xyz + p.y * l.axisV.xyz);
}

// A light's cube as the taps need it: each face's tile, and what all six share.
struct AreaShadowCube {
  vec4 tiles[6];
  float nearPlane, farPlane;
  float texelPerMetre;  // GpuShadowView::params.z
  float tanHalf;        // the faces' tan(fov / 2), guard band included
  vec2 atlasTexel;
};

AreaShadowCube areaShadowCube(uint first) {
  AreaShadowCube c;
  for (int f = 0; f < 6; ++f) c.tiles[f] = shadowViews[first + uint(f)].tile;
  vec4 params = shadowViews[first].params;
  c.nearPlane = params.x;
  c.farPlane = params.y;
  c.texelPerMetre = params.z;
  c.atlasTexel = 1.0 / vec2(textureSize(lightShadowAtlas, 0));
  c.tanHalf = 0.5 * params.z * c.tiles[0].z / c.atlasTexel.x;  // params.z = 2 tan / tile texels
  return c;
}

// One tap: the point where the ray from the light along `direction` (any length) meets the
// receiver's plane (through `onPlane`, unit `normal`; a ray along the plane keeps the receiver's
// distance), in the cube face that owns the direction (tlCubeFaceProject: no matrix): its atlas
// uv, its biased map depth and its view depth.
struct AreaShadowTap {
  vec2 uv;
  float depth;
  float w;
};

AreaShadowTap areaShadowTap(AreaShadowCube cube, vec3 lightPosition, vec3 direction, vec3 onPlane, vec3 normal, float distance) {
  direction = normalize(direction);
  float facing = dot(normal, direction);
  float t = abs(facing) > 1e-4 ? dot(normal, onPlane - lightPosition) / facing : distance;
  t = clamp(t, 0.5 * distance, 2.0 * distance);
  uint face = tlCubeFace(direction);
  vec3 p = tlCubeFaceProject(face, direction);
  vec4 tile = cube.tiles[face];
  vec2 lo = tile.xy + 1.5 * cube.atlasTexel, hi = tile.xy + tile.zw - 1.5 * cube.atlasTexel;
  AreaShadowTap tap;
  tap.uv = clamp(tile.xy + (p.xy / cube.tanHalf * 0.5 + 0.5) * tile.zw, lo, hi);
  tap.w = p.z * t;
  tap.depth = tlShadowViewDepth(cube.nearPlane, cube.farPlane, tap.w - kLightShadowBiasTexels * cube.texelPerMetre * t);
  return tap;
}

float areaShadowVisibility(uint lightIndex, vec3 position, vec3 normal) {
  GpuLight l = lights[lightIndex];
  uint first = l.shadowView;
  vec3 lightPosition = l.position.xyz;
  float distance = length(position - lightPosition);
  AreaShadowCube cube = areaShadowCube(first);
  if (distance <= cube.nearPlane) return 1.0;  // closer than the views' near plane: nothing between
  // The punctual lookup's normal offset, by the texel at the receiver.
  float texel = cube.texelPerMetre * distance;
  float cosine = dot(normal, (lightPosition - position) / distance);
  float slope = sqrt(max(1.0 - cosine * cosine, 0.0));
  vec3 shifted = position + normal * (kLightShadowNormalOffsetTexels * texel * max(slope, 0.2));
  vec3 centreRay = shifted - lightPosition;
  float reach = length(centreRay);
  vec3 axis = centreRay / reach;
  // Rotated per receiver (a hash of its position: the voxelizer has no pixel), so the taps'
  // pattern becomes fine noise rather than sixteen copies of the shadow; and, where the includer
  // accumulates frames (TL_AREA_SHADOW_PER_FRAME: lights.direct), per frame, so the noise averages out.
  uvec3 bits = floatBitsToUint(position * 64.0);
  uint seed = bits.x * 73856093u ^ bits.y * 19349663u ^ bits.z * 83492791u;
#ifdef TL_AREA_SHADOW_PER_FRAME
  seed ^= frame.frameIndex * 2654435761u;
  seed ^= seed >> 15;
  seed *= 2246822519u;
#endif
  float angle = 6.2831853 * float(seed & 0xFFFFu) / 65536.0;
  mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
  // The offsets' scale, as a tangent seen from the light, is capped at kAreaShadowMaxTan.
  float shapeSize = 0.0;
  for (int i = 0; i < 4; ++i) shapeSize = max(shapeSize, length(areaShadowShapePoint(l, vec2(i == 0 ? 1.0 : i == 1 ? -1.0 : 0.0, i == 2 ? 1.0 : i == 3 ? -1.0 : 0.0), axis)));
  float maxScale = kAreaShadowMaxTan * reach / max(shapeSize, 1e-6);

  // Blockers: anything between the receiver and the shape from a third of the way on (1/s - 1
  // up to 2) lies within the search. Eight taps (every other of the disk's) find them; the filter
  // needs the sixteen.
  float searchScale = min(2.0, maxScale);
  float blockerFraction = 0.0, blockers = 0.0;
  for (int i = 0; i < 16; i += 2) {
    vec3 q = areaShadowShapePoint(l, rotation * kPoissonDisk16[i], axis);
    AreaShadowTap tap = areaShadowTap(cube, lightPosition, centreRay + searchScale * q, shifted, normal, reach);
    float d = textureLod(lightShadowDepth, tap.uv, 0.0).r;
    if (d < tap.depth) {
      blockerFraction += tlShadowViewW(cube.nearPlane, cube.farPlane, d) / tap.w;
      blockers += 1.0;
    }
  }
  if (blockers == 0.0) return 1.0;
  float s = clamp(blockerFraction / blockers, 1e-3, 1.0);
  float scale = min(1.0 / s - 1.0, maxScale);
  // Every search tap blocked and the filter inside the search (blockers from a third of the way
  // on): the shape is hidden.
  if (blockers == 8.0 && scale <= searchScale) return 0.0;
  // A penumbra narrower than the map resolves: the punctual filter.
  if (scale * shapeSize < 1.5 * texel) return punctualShadowVisibility(lightIndex, position, normal);
  // Each tap stands for its point of the shape and weighs what that point sends the receiver
  // (cos cos / d^2; a tube's ribbon faces the receiver), so the visibility is the shadowed share
  // of the irradiance, not of the shape's area: the near side of a large light counts more.
  bool tube = l.type == kLightTube, twoSided = l.axisV.w > 0.5;
  float sum = 0.0, weights = 0.0;
  for (int i = 0; i < 16; ++i) {
    vec3 q = areaShadowShapePoint(l, rotation * kPoissonDisk16[i], axis);
    vec3 toPoint = lightPosition + q - position;
    float d2 = max(dot(toPoint, toPoint), 1e-8);
    float cosLight = tube ? sqrt(d2) : (twoSided ? abs(dot(l.direction.xyz, toPoint)) : max(-dot(l.direction.xyz, toPoint), 0.0));
    float weight = max(dot(normal, toPoint), 0.0) * cosLight / (d2 * d2);
    AreaShadowTap tap = areaShadowTap(cube, lightPosition, centreRay + scale * q, shifted, normal, reach);
    sum += weight * texture(lightShadowAtlas, vec3(tap.uv, tap.depth));
    weights += weight;
  }
  return weights > 0.0 ? sum / weights : 1.0;
}

// 1 for a light without a map.
float lightShadowVisibility(uint lightIndex, vec3 position, vec3 normal) {
  if (lights[lightIndex].shadowView == kNoLightShadow) return 1.0;
  return tlIsAreaLight(lights[lightIndex].type) ? areaShadowVisibility(lightIndex, position, normal)
                                                : punctualShadowVisibility(lightIndex, position, normal);
}
