#include "scene/material_average.h"

#include "shared/color.h"
#include "shared/rt.h"

namespace tl::scene {

glm::vec4 textureAverage(const Texture& t) {
  const size_t n = size_t(t.width) * t.height;
  if (n == 0) return glm::vec4(1.0f);
  glm::dvec4 sum(0.0);
  for (size_t i = 0; i < n; ++i) {
    glm::vec4 c = texelValue(t, i);
    // Half-float texels are linear already (float images, 16-bit colour decoded on load).
    if (t.srgb && t.format != TexelFormat::Rgba16Float) c = glm::vec4(shared::tlSrgbToLinear(glm::vec3(c)), c.a);
    sum += glm::dvec4(c);
  }
  return glm::vec4(sum / double(n));
}

// The texture's mean over its whole image: a transform that shows part of it, and vertex
// colours, are not weighed in (this is the far-field average, not a per-texel value).
namespace {
glm::vec3 averageBaseColor(const Scene& scene, const Material& m) {
  glm::vec3 base = glm::vec3(m.baseColorFactor);
  if (m.baseColorTexture && m.baseColorTexture->texture < scene.textures.size())
    base *= glm::vec3(textureAverage(scene.textures[m.baseColorTexture->texture]));
  return glm::clamp(base, 0.0f, 1.0f);
}
}  // namespace

// An unlit material (KHR_materials_unlit, shared/scene.h) reflects nothing and emits its base colour.
glm::vec3 materialAverageAlbedo(const Scene& scene, const Material& m, uint32_t materials) {
  if (m.unlit) return glm::vec3(0.0f);
  glm::vec3 base = averageBaseColor(scene, m);
  float metallic = m.metallic;
  if (m.metallicRoughnessTexture && m.metallicRoughnessTexture->texture < scene.textures.size())
    metallic *= textureAverage(scene.textures[m.metallicRoughnessTexture->texture]).b;
  return shared::tlMaterialHitAlbedo(glm::clamp(base, 0.0f, 1.0f), glm::clamp(metallic, 0.0f, 1.0f), materials);
}

glm::vec3 materialAverageEmission(const Scene& scene, const Material& m) {
  glm::vec3 e = m.emissiveFactor * m.emissiveStrength;
  if (m.emissiveTexture && m.emissiveTexture->texture < scene.textures.size())
    e *= glm::vec3(textureAverage(scene.textures[m.emissiveTexture->texture]));
  if (m.unlit) e += averageBaseColor(scene, m);
  return e;
}

}  // namespace tl::scene
