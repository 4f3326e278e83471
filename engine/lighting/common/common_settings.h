// The settings every path shares: the image, materials, the sun's and the lights' shadow maps,
// the indirect specular switch, redeferred shading and TAA.
// One line per setting, the columns of TL_RENDER_SETTINGS (render_settings.h), which gathers
// this group and names its owner: `owner` below is that name, so no line restates it.
// A new setting of this group is one line here.
#pragma once

// clang-format off
#define TL_COMMON_SETTINGS(X, owner) \
  X(uint32_t, width, 640, 1, 16384, "px", owner, "", kSettingNoPanel, "image width (--size)") \
  X(uint32_t, height, 360, 1, 16384, "px", owner, "", kSettingNoPanel, "image height (--size)") \
  X(MaterialMode, materials, MaterialMode::Authored, 0, 2, "", owner, "reference rt legacy direct", kSettingPlain, "material override, every path and the reference: authored, diffuse (Lambert, authored base colour) or clay (Lambert 0.8 grey); emission stays") \
  X(uint32_t, shadowMapSize, 2048, 64, 8192, "texels", owner, "", kSettingTune, "side of the sun's shadow map") \
  X(float, shadowDepthBiasTexels, 1.5f, 0.0f, 16.0f, "texels", owner, "", kSettingPlain, "sun shadow constant depth bias, in shadow-map texels of depth") \
  X(float, shadowNormalOffsetTexels, 1.0f, 0.0f, 16.0f, "texels", owner, "", kSettingPlain, "sun shadow lookup offset along the normal, in shadow-map texels") \
  X(bool, softShadows, true, 0, 1, "", owner, "", kSettingTune, "PCSS: penumbrae from the sun's angular size (off: 3x3 PCF, --hard-shadows)") \
  X(float, pcssMaxRadiusTexels, 16.0f, 0.0f, 64.0f, "texels", owner, "", kSettingPlain, "widest PCSS filter") \
  X(uint32_t, lightShadowMapSize, 512, 64, 4096, "texels", owner, "legacy direct", kSettingTune, "side of each shadow-map view of a point, spot or area light (a point or area light has six; direct and legacy paths)") \
  X(uint32_t, lightShadowMaxLights, 8, 0, 32, "", owner, "legacy direct", kSettingPlain, "the most powerful point, spot and area lights that cast shadows in the direct and legacy paths (0: none; rt and the reference trace every light)") \
  X(bool, specularGi, true, 0, 1, "", owner, "", kSettingTune | kSettingFeature, "indirect specular from the path's SH (dominant direction, GGX; Metro); off: the sky's specular times AO") \
  X(bool, redeferred, false, 0, 1, "", owner, "", kSettingPlain, "redeferred shading (Fools Engine): lights accumulate material-free sums (ibuffer.*), one material pass applies the materials; off: the deferred composite") \
  X(float, redeferredRate, 1.0f, 0.25f, 1.0f, "", owner, "", kSettingPow2, "redeferred: share of pixels the illumination passes shade first (1 all, 0.5 a checkerboard, 0.25 one of each 2x2); the rest filled depth- and normal-aware, edges of geometry and light shaded at full rate") \
  X(bool, taa, false, 0, 1, "", owner, "", kSettingPlain, "temporal anti-aliasing: jittered projection, YCoCg-clipped history (not the reference, which jitters its own rays)") \
  X(float, taaBlend, 0.1f, 0.01f, 1.0f, "", owner, "", kSettingPlain, "TAA: weight of the new frame in the history; lower is smoother and slower to follow")
// clang-format on
