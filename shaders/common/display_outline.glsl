// Outline of the selected instance: pixels of it whose 4-neighbourhood leaves it.
vec3 outline(ivec2 p, ivec2 size, vec3 c) {
  if (push.selectedId == 0u) return c;
  ivec2 idSize = textureSize(instanceId, 0);
  ivec2 q = ivec2((vec2(p) + 0.5) / vec2(size) * vec2(idSize));
  uint self = texelFetch(instanceId, q, 0).r;
  bool inside = self == push.selectedId;
  bool edge = false;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = q + ivec2(i == 0 ? 1 : i == 1 ? -1 : 0, i == 2 ? 1 : i == 3 ? -1 : 0);
    o = clamp(o, ivec2(0), idSize - 1);
    edge = edge || ((texelFetch(instanceId, o, 0).r == push.selectedId) != inside);
  }
  if (edge) return vec3(1.0, 0.55, 0.05);
  return inside ? mix(c, vec3(1.0, 0.55, 0.05), 0.12) : c;
}
