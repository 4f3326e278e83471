// Sun visibility through the shadow map, shared by the composite and the voxelizer. The
// includer declares `frame` (FrameConstants) and `sunShadow` (sampler2DShadow).
// 3x3 PCF of hardware 2x2 comparisons. Receivers are pushed along the normal by a few
// texels and towards the sun by the depth bias, both in world units, which keeps acne
// away at any distance from the origin.
float sunVisibility(vec3 position, vec3 normal) {
  if ((frame.flags & kFrameFlagSunShadows) == 0u) return 1.0;
  vec3 l = frame.sunToLight.xyz;
  float texel = frame.shadowParams.x;
  float slope = sqrt(max(1.0 - dot(normal, l) * dot(normal, l), 0.0));
  vec3 offset = normal * (frame.shadowParams.z * texel * max(slope, 0.2)) + l * frame.shadowParams.y;
  vec4 clip = frame.sunViewProj * vec4(position + offset, 1.0);
  vec3 s = clip.xyz / clip.w;
  vec2 uv = s.xy * 0.5 + 0.5;
  if (s.z >= 1.0) return 1.0;
  float size = frame.shadowParams.w;
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(sunShadow, vec3(uv + vec2(x, y) / size, s.z));
  return sum / 9.0;
}

