// Area lights of the light table (shared/lights.h GpuLight, types kLightRect, kLightDisk,
// kLightTube): the one physics every path shades them with. Included by shared/lights.h after
// GpuLight and LightIncidence; compiled as C++ too, so the unit tests check it against closed
// forms without a GPU.
//
// An area light is a Lambertian emitter of radiance L (GpuLight::intensity.rgb, Twinlight units:
// nits / 683) on a flat shape: a rectangle (half-extent vectors axisU, axisV), a disk (axisU,
// axisV both of length r) or a tube of length 2|axisU| and radius axisU.w. A tube is shaded as
// the ribbon of width 2r through its axis that faces the shading point: that ribbon's projected
// area along any direction is the cylinder's (2 r length sin theta), so it sends what the
// cylinder's side sends (its caps left out). One-sided shapes emit along GpuLight::direction
// (their front normal); axisV.w = 1 makes rectangles and disks emit from both faces; a tube
// always does. Lights are emitters that block nothing: shadow rays pass through them, and no
// path shows them to the camera (the reference shows them in reflections, through the BRDF's
// rays): see docs/design/lights.md.
//
// Three ways to shade one, all of the same shape and radiance:
//   tlAreaLightAnalytic  the unshadowed vector irradiance F (Lambert's polygon formula, a disk as
//                        a 32-gon of the same area): irradiance |F| from direction F/|F|, so a
//                        Lambertian surface facing any way with the whole light above its horizon
//                        gets exactly E = n.F (the rasterising paths' diffuse layer; their
//                        glossy lobes sample the shape instead: shared/area_specular.h)
//   tlAreaLightSample    a point drawn uniformly on the shape: irradiance L cos_l A / d^2 from it
//                        (one-sample estimate of the integral), pdf per steradian d^2 / (cos_l A)
//   tlAreaLightHit       where a ray meets the shape, and the pdf tlAreaLightSample gives that
//                        direction (multiple importance sampling in the reference)
#ifndef TL_SHARED_LIGHTS_H
#error "include shared/lights.h, not shared/area_lights.h"
#endif
#ifndef TL_SHARED_AREA_LIGHTS_H
#define TL_SHARED_AREA_LIGHTS_H

TL_BEGIN
// Edges of the polygon a disk's vector irradiance is computed over (its radius scaled so the
// polygon has the disk's area: on axis within 0.1% of the disk at any height, tests/unit).
TL_CONST uint kAreaDiskEdges = 32u;

TL_FN bool tlIsAreaLight(uint type) { return type >= kLightRect; }

// An area light's flat shape as seen from `position`: centre, half-extent vectors (u x v along
// the front normal), the normal, the area of one face and whether both faces emit. A tube's
// ribbon turns to face the point; on the tube's axis line it has no area.
struct AreaShape {
  vec3 centre;
  vec3 u;
  vec3 v;
  vec3 normal;
  float area;
  float twoSided;
};

TL_FN AreaShape tlAreaShape(GpuLight light, vec3 position) {
  AreaShape s;
  s.centre = vec3(light.position);
  s.u = vec3(light.axisU);
  s.v = vec3(light.axisV);
  s.normal = vec3(light.direction);
  s.twoSided = light.axisV.w;
  if (light.type == kLightTube) {
    vec3 w = cross(s.u, position - s.centre);
    float lw = length(w);
    s.v = lw > 1e-12f ? w * (light.axisU.w / lw) : vec3(0.0f);
    s.normal = lw > 1e-12f ? normalize(cross(s.v, s.u)) : vec3(0.0f);
    s.twoSided = 1.0f;
  }
  s.area = light.type == kLightDisk ? kPi * dot(s.u, s.u) : 4.0f * length(s.u) * length(s.v);
  return s;
}

// Which side of the shape `position` is on: > 0 in front, < 0 behind, 0 when the shape
// cannot light it (behind a one-sided shape, in its plane, or no area).
TL_FN float tlAreaSide(AreaShape s, vec3 position) {
  if (!(s.area > 0.0f)) return 0.0f;
  float side = dot(position - s.centre, s.normal);
  if (side > 0.0f || (side < 0.0f && s.twoSided > 0.5f)) return side;
  return 0.0f;
}

// One edge's term of Lambert's formula: theta times the unit normal of the plane through the
// point and the edge (a, b: unit directions to the edge's ends); atan2 keeps small angles exact.
TL_FN vec3 tlEdgeIntegral(vec3 a, vec3 b) {
  vec3 c = cross(a, b);
  float s = length(c);
  return s > 0.0f ? c * (atan(s, dot(a, b)) / s) : vec3(0.0f);
}

TL_FN vec3 tlAreaCorner(AreaShape s, vec3 position, float a, float b) { return normalize(s.centre + a * s.u + b * s.v - position); }

// Unit-radiance vector irradiance of the shape at `position`: E = n.F on a surface of normal n
// that sees the whole shape above its horizon. Points towards the shape's plane.
TL_FN vec3 tlAreaVectorIrradiance(GpuLight light, AreaShape s, vec3 position, float side) {
  vec3 f = vec3(0.0f);
  if (light.type == kLightDisk) {
    // The regular polygon of the disk's area: circumradius r sqrt(pi / (N/2 sin(2 pi / N))).
    float step = 2.0f * kPi / float(kAreaDiskEdges);
    float scale = sqrt(kPi / (0.5f * float(kAreaDiskEdges) * sin(step)));
    vec3 first = tlAreaCorner(s, position, scale, 0.0f), previous = first;
    for (uint i = 1u; i < kAreaDiskEdges; ++i) {
      float phi = step * float(i);
      vec3 next = tlAreaCorner(s, position, scale * cos(phi), scale * sin(phi));
      f += tlEdgeIntegral(previous, next);
      previous = next;
    }
    f += tlEdgeIntegral(previous, first);
  } else {
    vec3 c0 = tlAreaCorner(s, position, -1.0f, -1.0f), c1 = tlAreaCorner(s, position, 1.0f, -1.0f);
    vec3 c2 = tlAreaCorner(s, position, 1.0f, 1.0f), c3 = tlAreaCorner(s, position, -1.0f, 1.0f);
    f = tlEdgeIntegral(c0, c1) + tlEdgeIntegral(c1, c2) + tlEdgeIntegral(c2, c3) + tlEdgeIntegral(c3, c0);
  }
  f *= 0.5f;
  // The winding decides F's sign: the light lies on the side of the plane opposite `side`.
  if (dot(f, s.normal) * side > 0.0f) f = -f;
  return f;
}

TL_FN LightIncidence tlAreaNoIncidence(vec3 toLight, float distance) {
  LightIncidence li;
  li.toLight = toLight;
  li.distance = distance;
  li.irradiance = vec3(0.0f);
  li.pdf = 0.0f;
  return li;
}

// The unshadowed light of the whole shape (deterministic: the rasterising paths).
TL_FN LightIncidence tlAreaLightAnalytic(GpuLight light, vec3 position) {
  AreaShape s = tlAreaShape(light, position);
  vec3 toCentre = s.centre - position;
  float distance = max(length(toCentre), 1e-6f);
  LightIncidence li = tlAreaNoIncidence(toCentre / distance, distance);
  float side = tlAreaSide(s, position);
  if (side == 0.0f) return li;
  vec3 f = tlAreaVectorIrradiance(light, s, position, side);
  float e = length(f);
  if (!(e > 0.0f)) return li;
  li.toLight = f / e;
  li.irradiance = vec3(light.intensity) * e;
  return li;
}

// A point of the shape drawn uniformly by u (area pdf 1 / A): the light from it as irradiance
// at normal incidence over the pdf per steradian. irradiance 0 (pdf 0) where it faces away.
TL_FN LightIncidence tlAreaLightSample(GpuLight light, vec3 position, vec2 u) {
  AreaShape s = tlAreaShape(light, position);
  vec3 onLight;
  if (light.type == kLightDisk) {
    vec2 d = tlSampleConcentricDisk(u);
    onLight = s.centre + d.x * s.u + d.y * s.v;
  } else {
    onLight = s.centre + (2.0f * u.x - 1.0f) * s.u + (2.0f * u.y - 1.0f) * s.v;
  }
  vec3 d = onLight - position;
  float d2 = dot(d, d);
  float distance = sqrt(d2);
  if (!(distance > 1e-6f) || tlAreaSide(s, position) == 0.0f) return tlAreaNoIncidence(vec3(0.0f, 1.0f, 0.0f), 1.0f);
  LightIncidence li = tlAreaNoIncidence(d / distance, distance);
  float cosLight = abs(dot(s.normal, li.toLight));
  if (!(cosLight > 0.0f)) return li;
  li.pdf = d2 / (cosLight * s.area);
  li.irradiance = vec3(light.intensity) / li.pdf;
  return li;
}

// Where the ray origin + t dir (dir unit) meets the shape's emitting face (t < 0: nowhere), and
// the solid-angle pdf tlAreaLightSample from `origin` has for dir.
struct AreaHit {
  float t;
  float pdf;
};
TL_FN AreaHit tlAreaLightHit(GpuLight light, vec3 origin, vec3 dir) {
  AreaShape s = tlAreaShape(light, origin);
  AreaHit h;
  h.t = -1.0f;
  h.pdf = 0.0f;
  float facing = dot(dir, s.normal);  // < 0: the ray meets the front face
  if (!(s.area > 0.0f) || facing == 0.0f || (facing > 0.0f && s.twoSided < 0.5f)) return h;
  float t = dot(s.centre - origin, s.normal) / facing;
  if (!(t > 0.0f)) return h;
  vec3 q = origin + t * dir - s.centre;
  float a = dot(q, s.u) / dot(s.u, s.u), b = dot(q, s.v) / dot(s.v, s.v);
  bool inside = light.type == kLightDisk ? a * a + b * b <= 1.0f : abs(a) <= 1.0f && abs(b) <= 1.0f;
  if (!inside) return h;
  h.t = t;
  h.pdf = t * t / (abs(facing) * s.area);
  return h;
}

// The power heuristic (Veach, beta 2): the weight of a sample drawn with density `chosen` when
// `other` could have drawn it too.
TL_FN float tlPowerHeuristic(float chosen, float other) {
  float a = chosen * chosen, b = other * other;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}
TL_END

#endif
