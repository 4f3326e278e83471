// The environment map's texels and their importance table (shared/environment.h), as the
// reference path samples them and every path's background shows them. The includer includes
// shared/frame.h and shared/environment.h and declares `frame`; the table is bound only in
// frames with kFrameFlagEnvironment (an optional binding: no code reads it otherwise).
layout(std430, set = 0, binding = kBindingEnvironment) readonly buffer EnvironmentTable { float envTable[]; };

bool environmentMapOn() { return (frame.flags & kFrameFlagEnvironment) != 0u; }
vec2 environmentRotation() { return frame.envParams.xy; }

// The texel a map-frame (u, v) falls in.
uvec2 environmentTexel(vec2 uv) {
  return min(uvec2(uv * vec2(frame.envWidth, frame.envHeight)), uvec2(frame.envWidth - 1u, frame.envHeight - 1u));
}

// Radiance arriving from world direction `dir`: the map's texel (times the intensity), or the
// uniform sky without a map.
vec3 environmentRadiance(vec3 dir) {
  if (!environmentMapOn()) return frame.skyRadiance.rgb;
  uvec2 t = environmentTexel(tlEquirectUv(tlEnvWorldToMap(dir, environmentRotation())));
  uint i = 4u * (t.y * frame.envWidth + t.x);
  return vec3(envTable[i], envTable[i + 1u], envTable[i + 2u]) * frame.envParams.z;
}

// Probability of a cell of a CDF stored at base .. base + n.
float environmentCdfStep(uint base, uint i) { return envTable[base + i + 1u] - envTable[base + i]; }

// The largest i < n with cdf[base + i] <= u (cdf[base] = 0, cdf[base + n] = 1).
uint environmentSearch(uint base, uint n, float u) {
  uint lo = 0u, hi = n;
  while (hi - lo > 1u) {
    uint mid = (lo + hi) / 2u;
    if (envTable[base + mid] <= u) lo = mid;
    else hi = mid;
  }
  return lo;
}

// Solid-angle density of sampling world direction `dir` by environmentSample.
float environmentPdf(vec3 dir) {
  vec2 uv = tlEquirectUv(tlEnvWorldToMap(dir, environmentRotation()));
  uvec2 t = environmentTexel(uv);
  uint w = frame.envWidth, h = frame.envHeight;
  float p = environmentCdfStep(tlEnvMarginalOffset(w, h), t.y) * environmentCdfStep(tlEnvConditionalOffset(w, h, t.y), t.x);
  float sinTheta = sin(kPi * uv.y);
  return sinTheta > 0.0 ? p * float(w * h) / (2.0 * kPi * kPi * sinTheta) : 0.0;
}

// A world direction drawn in proportion to luminance x sin(theta) (piecewise constant over
// the texels, uniform in (u, v) inside one), and its solid-angle density.
vec3 environmentSample(vec2 u, out float pdf) {
  uint w = frame.envWidth, h = frame.envHeight;
  uint marginal = tlEnvMarginalOffset(w, h);
  uint r = environmentSearch(marginal, h, u.y);
  float pr = environmentCdfStep(marginal, r);
  float fy = pr > 0.0 ? clamp((u.y - envTable[marginal + r]) / pr, 0.0, 1.0) : 0.5;
  uint row = tlEnvConditionalOffset(w, h, r);
  uint c = environmentSearch(row, w, u.x);
  float pc = environmentCdfStep(row, c);
  float fx = pc > 0.0 ? clamp((u.x - envTable[row + c]) / pc, 0.0, 1.0) : 0.5;
  vec2 uv = vec2((float(c) + fx) / float(w), (float(r) + fy) / float(h));
  float sinTheta = sin(kPi * uv.y);
  pdf = sinTheta > 0.0 ? pr * pc * float(w * h) / (2.0 * kPi * kPi * sinTheta) : 0.0;
  return tlEnvMapToWorld(tlEquirectDirection(uv), environmentRotation());
}

// Multiple importance sampling (the power heuristic) of a direction one strategy drew with
// density `a` against the other's density `b` for the same direction.
float environmentMisWeight(float a, float b) { return a * a / max(a * a + b * b, 1e-30); }
