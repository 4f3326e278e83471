// Outline of the selected instance: texels of it whose 4-neighbourhood leaves it, at `uv`
// of the frame (the display may be zoomed). Inside, its own colour, untinted: the colour an
// artist edits (an albedo override) is the colour shown.
vec3 outline(vec2 uv, vec3 c) {
  if (push.selectedId == 0u || any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return c;
  ivec2 idSize = textureSize(instanceId, 0);
  ivec2 q = ivec2(uv * vec2(idSize));
  uint self = texelFetch(instanceId, q, 0).r;
  bool inside = self == push.selectedId;
  bool edge = false;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = q + ivec2(i == 0 ? 1 : i == 1 ? -1 : 0, i == 2 ? 1 : i == 3 ? -1 : 0);
    o = clamp(o, ivec2(0), idSize - 1);
    edge = edge || ((texelFetch(instanceId, o, 0).r == push.selectedId) != inside);
  }
  return edge ? vec3(1.0, 0.55, 0.05) : c;
}

// The source UV a display pixel shows, and whether it is a texel border when zoomed in.
vec2 sourceUv(ivec2 p, ivec2 size) { return push.window.xy + (vec2(p) + 0.5) / vec2(size) * push.window.zw; }
vec3 grid(vec2 uv, ivec2 size, ivec2 sourceSize, vec3 c) {
  vec2 texelsPerPixel = push.window.zw * vec2(sourceSize) / vec2(size);
  if ((push.flags & kDisplayFlagGrid) == 0u || max(texelsPerPixel.x, texelsPerPixel.y) > 1.0 / 8.0) return c;
  vec2 f = fract(uv * vec2(sourceSize));
  return any(lessThan(f, texelsPerPixel)) ? mix(c, vec3(0.5), 0.6) : c;
}
