#version 460
// Horizon-based ambient occlusion (GTAO, Jimenez et al. 2016): per slice direction the two
// horizons are found by marching the depth buffer within the radius, then the visible arc is
// integrated cosine-weighted against the normal projected into the slice. A horizon only
// falls back slowly when later samples drop behind it (the thickness heuristic): thin
// occluders in front of the surface do not hide the sky behind them completely.
#extension GL_GOOGLE_include_directive : require
#include "legacy/legacy_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kLegacyBindingAoRaw, rg16f) uniform writeonly image2D aoOut;  // AO, view depth

const float kHalfPi = 1.5707963;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, reducedSize(push.aoDivisor)))) return;
  ivec2 p = fullPixel(q, push.aoDivisor);
  ivec2 size = ivec2(frame.viewport.xy);
  float depth = texelFetch(gDepth, p, 0).r;
  if (depth <= 0.0) {
    imageStore(aoOut, q, vec4(1.0, 0.0, 0.0, 0.0));
    return;
  }
  vec3 P = pixelPosition(p, depth);
  vec3 n = pixelNormal(p);
  vec3 V = towardsViewer(P);
  float w = viewW(P);
  // Radius in pixels at this distance; at least a few pixels, at most a fifth of the screen.
  float radiusPixels = clamp(push.aoRadius / pixelFootprint(w), 2.0, 0.2 * frame.viewport.y);
  uint steps = max(push.aoSteps, 1u), slices = max(push.aoSlices, 1u);
  float stepPixels = radiusPixels / float(steps);
  // 2x2 interleaved rotation: the four half-resolution pixels a full-resolution pixel is
  // filtered from take four different sets of directions.
  // The pattern turns by a golden-ratio step each frame, so the temporal filter gathers new
  // directions while the camera holds still.
  float rotation = fract((float(((q.y & 1) << 1) | ((q.x & 1) ^ (q.y & 1))) + 0.5) / 4.0 +
                         float(frame.frameIndex & 255u) * 0.618034 / 4.0);

  // Self-normalised over the slices: a slice of an unoccluded surface seen at an angle
  // integrates to lenN (cos g + g sin g), which is 1 only on average over all directions, so
  // with a few slices the ratio to that unoccluded value is used (exactly 1 on open ground).
  float visibility = 0.0, unoccluded = 0.0;
  for (uint s = 0u; s < slices; ++s) {
    float phi = (float(s) + rotation) * 3.14159265 / float(slices);
    vec2 dir = vec2(cos(phi), sin(phi));
    // The slice plane in world space: the view vector and the screen direction at P's depth.
    vec3 side = pixelPosition(p + ivec2(round(dir * 4.0)), depth) - P;
    vec3 T = normalize(side - V * dot(side, V));
    vec3 axis = normalize(cross(T, V));
    vec3 projN = n - axis * dot(n, axis);
    float lenN = length(projN);
    if (lenN < 1e-4) continue;  // the normal is along the slice axis: the slice sees nothing
    float cosN = clamp(dot(projN / lenN, V), -1.0, 1.0);
    float gamma = (dot(projN, T) >= 0.0 ? 1.0 : -1.0) * acos(cosN);
    float horizon[2];
    for (int sideIndex = 0; sideIndex < 2; ++sideIndex) {
      float sgn = sideIndex == 0 ? -1.0 : 1.0;
      float best = -1.0;
      for (uint k = 1u; k <= steps; ++k) {
        ivec2 sp = p + ivec2(round(dir * sgn * stepPixels * (float(k) - 0.5 * rotation)));
        if (any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, size)) || sp == p) continue;
        float sd = texelFetch(gDepth, sp, 0).r;
        if (sd <= 0.0) continue;
        vec3 H = pixelPosition(sp, sd) - P;
        float dist = length(H);
        if (dist >= push.aoRadius) continue;  // beyond the radius: not an occluder at all
        // Within 6 degrees of the tangent plane: depth-buffer rounding on a flat surface seen at
        // a grazing angle, not an occluder (without this, distant floors go grey in bands).
        if (dot(H, n) <= 0.1 * dist) continue;
        // Occluders fade out over the outer 30% of the radius.
        float falloff = clamp((push.aoRadius - dist) / (0.3 * push.aoRadius), 0.0, 1.0);
        float c = mix(-1.0, dot(H, V) / max(dist, 1e-6), falloff);
        best = c > best ? c : mix(best, c, push.aoThickness);
      }
      float h = sgn * acos(clamp(best, -1.0, 1.0));
      // Clamp the horizon to the hemisphere around the projected normal.
      horizon[sideIndex] = sideIndex == 0 ? gamma + max(h - gamma, -kHalfPi) : gamma + min(h - gamma, kHalfPi);
    }
    float cg = cos(gamma), sg = sin(gamma);
    float arc0 = -cos(2.0 * horizon[0] - gamma) + cg + 2.0 * horizon[0] * sg;
    float arc1 = -cos(2.0 * horizon[1] - gamma) + cg + 2.0 * horizon[1] * sg;
    visibility += lenN * 0.25 * (arc0 + arc1);
    unoccluded += lenN * (cg + gamma * sg);
  }
  // The view depth rides along for the upsample's depth weights (no second fetch there).
  imageStore(aoOut, q, vec4(unoccluded > 1e-4 ? clamp(visibility / unoccluded, 0.0, 1.0) : 1.0, depthToViewW(depth), 0.0, 0.0));
}
