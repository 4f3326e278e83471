// Visibility of a point or spot light through its shadow map (shared/lights.h GpuShadowView),
// for the direct and legacy paths. The includer includes shared/lights.h and declares `lights`
// (the light table, common/lights.glsl) before including this.
layout(set = 0, binding = kBindingLightShadowViews, std430) readonly buffer LightShadowViews { GpuShadowView shadowViews[]; };
layout(set = 0, binding = kBindingLightShadowAtlas) uniform sampler2DShadow lightShadowAtlas;

// 3x3 PCF of hardware 2x2 comparisons: punctual lights cast hard shadows (as the traced paths'
// shadow rays give), filtered over a texel or two. The receiver (camera-relative `position`,
// unit `normal`) is pushed along its normal and towards the light by a few texels of the map at
// its distance. 1 for a light without a map.
float lightShadowVisibility(uint lightIndex, vec3 position, vec3 normal) {
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
