// Emissive triangles as both ray tracers sample them (next-event estimation): the reference
// (reference/path.glsl) and the RT path's pixels and hits (rt/hit_lighting.glsl) draw one
// triangle in proportion to its power, area x the luminance of its material's average
// emission, from one alias table (Walker 1977, Vose 1991: O(1) per draw, the exact probability of
// any triangle in O(1), which a BRDF ray that hits an emitter needs for its MIS weight), then a
// point uniform in area on it. The table is built once per scene on the CPU
// (lighting/common/emitter_table.h); every triangle of an emissive instance has an entry, in
// the mesh's order, so entry = the instance's first + the triangle's index.
//
// The RT path reads the world-space corners and the average radiance; the reference rebuilds
// the triangle from the instance's camera-relative transform and its vertices (exact far from
// the origin and for deforming meshes) and reads the material's emission at the point, texture
// and all: the average only chooses, the estimate weighs what the point emits by the exact pdf.
#ifndef TL_SHARED_EMITTERS_H
#define TL_SHARED_EMITTERS_H
#include "common.h"
#include "sampling.h"

TL_BEGIN
struct Emitter {
  vec4 p0;        // xyz: world position of the first corner (rest pose); w: the alias slot's threshold
  vec4 edge1;     // xyz: p1 - p0; w: area (m^2, rest pose)
  vec4 edge2;     // xyz: p2 - p0; w: probability of choosing this triangle (what the alias table draws)
  vec4 radiance;  // rgb: average emitted radiance (factor x strength x texture average); w unused
  uvec4 ids;      // x: instance, y: triangle of its mesh, z: the alias slot's other triangle, w unused
};

// The alias table's draw from one 32-bit uniform h over `count` slots: its top 24 bits choose
// the slot, a hash of all of it decides between the slot's own triangle (below its threshold)
// and its alias. (The low bits of h are not used for the slot: of a PCG hash of pixel and frame
// they follow patterns a 2-triangle light showed as a bias.) Uniform to 2^-24 for up to 2^24 slots.
TL_FN uint tlAliasSlot(uint h, uint count) { return min(uint(tlUintToUnitFloat(h) * float(count)), count - 1u); }
TL_FN bool tlAliasKeepsSlot(uint h, float threshold) { return threshold >= 1.0f || tlUintToUnitFloat(tlPcgHash(h)) < threshold; }

// The barycentrics (of p1, p2) of a point uniform in area on a triangle (the square-root warp).
TL_FN vec2 tlEmitterBarycentrics(vec2 u) {
  float su = sqrt(u.x);
  return vec2(1.0f - su, u.y * su);
}
TL_FN vec3 tlEmitterPoint(Emitter e, vec2 u) {
  vec2 b = tlEmitterBarycentrics(u);
  return vec3(e.p0) + b.x * vec3(e.edge1) + b.y * vec3(e.edge2);
}
// The pdf in solid angle of a point drawn this way, seen from `distance2` away at `cosLight`
// to its triangle's normal: probability / area x d^2 / |cos|; both faces emit.
TL_FN float tlEmitterSolidAnglePdf(float probability, float area, float distance2, float cosLight) {
  return probability * distance2 / max(area * abs(cosLight), 1e-30f);
}
// Its inverse for the RT path's world-space corners (area and probability from the entry). The
// squared distance is kept above a millionth of the triangle's area (a share of its own size,
// not a length in metres) so a point touching the emitter does not divide by zero.
TL_FN float tlEmitterInversePdf(Emitter e, float distance2, float cosLight) {
  return e.edge1.w * abs(cosLight) / (max(distance2, 1e-6f * e.edge1.w) * max(e.edge2.w, 1e-30f));
}
TL_END

#ifdef __cplusplus
static_assert(sizeof(tl::shared::Emitter) == 80);
#endif
#endif
