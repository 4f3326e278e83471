// The environment map where the rt path's GI rays start (RtPush::environmentSampling: the
// pixels in rt/lighting.rgen, the disocclusion rays' pixels in rt/disocclusion.rgen), by multiple
// importance sampling of two strategies: the GI ray (cosine-distributed) that missed, and one
// direction drawn by the map's importance (luminance x sin(theta), common/environment.glsl)
// through a shadow ray; each weighed by the power heuristic against the other's density, so
// together they estimate the map's texels without bias where the order-2 SH (tlSkyRadiance)
// only approximates them. The first is the miss's radiance; the second an SH sample of its own
// density. Include after rt/hit_lighting.glsl (unoccluded); the table is bound only with
// RtPush::environmentSampling.
#include "common/environment.glsl"

float cosinePdf(vec3 n, vec3 d) { return max(dot(n, d), 0.0) * kInvPi; }

// The radiance a cosine-distributed GI ray from a surface of normal n brings back when it
// misses in direction dir: the map's texel, weighed against the importance sample.
vec3 environmentMiss(vec3 n, vec3 dir) {
  return environmentRadiance(dir) * environmentMisWeight(cosinePdf(n, dir), environmentPdf(dir));
}

// The importance sample from `origin` on a surface of normal n, as an SH sample.
ShLumaCoCg environmentSampleSh(vec3 origin, vec3 n, uvec3 seed) {
  float pdf;
  vec3 l = environmentSample(tlRandom2(seed), pdf);
  float c = dot(n, l);
  // The map is at infinity: the shadow ray passes everything in the scene, as the sun's does.
  if (c <= 0.0 || pdf <= 0.0 || unoccluded(origin, l, 1e30) == 0.0) return tlShZero();
  vec3 radiance = environmentRadiance(l) * environmentMisWeight(pdf, c * kInvPi);
  return tlShScale(tlShProjectRadiance(l, radiance), tlRtShWeightForPdf(c, 1.0 / pdf));
}
