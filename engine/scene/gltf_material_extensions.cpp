// The glTF material extensions that change how a surface reflects or lets light through
// (KHR_materials_ior, KHR_materials_specular, KHR_materials_unlit, KHR_materials_transmission,
// KHR_materials_volume, KHR_materials_clearcoat) and KHR_materials_pbrSpecularGlossiness, which
// is converted to the metal-rough model on import. Every value is checked as the float it is
// stored in (ImportValues), as the core material's are (gltf_materials.cpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/gltf_parts.h"
#include "scene/material_average.h"

namespace tl::scene {
namespace {

const tinygltf::Value* extension(const tinygltf::Material& gm, const char* name) {
  const auto it = gm.extensions.find(name);
  return it == gm.extensions.end() ? nullptr : &it->second;
}

float number(const tinygltf::Value& ext, const char* name, float fallback, ImportValues& values, const std::string& what) {
  if (!ext.Has(name)) return fallback;
  const auto& v = ext.Get(name);
  if (!v.IsNumber()) values.fail(fmt::format("{} {} is not a number", what, name));
  return values.finite(v.GetNumberAsDouble(), what + " " + name);
}

// `count` numbers, each clamped into [lo, hi].
template <int N>
glm::vec<N, float> numbers(const tinygltf::Value& ext, const char* name, glm::vec<N, float> fallback, float lo, float hi,
                           ImportValues& values, const std::string& what) {
  if (!ext.Has(name)) return fallback;
  const auto& v = ext.Get(name);
  if (!v.IsArray() || v.ArrayLen() != size_t(N)) values.fail(fmt::format("{} {} is not {} numbers", what, name, N));
  glm::vec<N, float> out;
  for (int c = 0; c < N; ++c) {
    if (!v.Get(c).IsNumber()) values.fail(fmt::format("{} {} is not {} numbers", what, name, N));
    out[c] = values.clamped(v.Get(c).GetNumberAsDouble(), lo, hi, fmt::format("{} {}", what, name));
  }
  return out;
}

}  // namespace

ExtensionTexture extensionTexture(const tinygltf::Value& ext, const char* name, ImportValues& values, const std::string& what) {
  ExtensionTexture t;
  if (!ext.Has(name)) return t;
  const auto& v = ext.Get(name);
  if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsInt())
    values.fail(fmt::format("{} {} is not a textureInfo with an index", what, name));
  t.index = v.Get("index").GetNumberAsInt();
  if (v.Has("texCoord") && v.Get("texCoord").IsInt()) t.texCoord = v.Get("texCoord").GetNumberAsInt();
  if (v.Has("extensions") && v.Get("extensions").IsObject())
    for (const auto& key : v.Get("extensions").Keys()) t.extensions[key] = v.Get("extensions").Get(key);
  return t;
}

void readReflectionExtensions(const tinygltf::Material& gm, Material& m, ImportValues& values, const std::string& what,
                              const TextureReader& texture) {
  if (const auto* ior = extension(gm, "KHR_materials_ior")) {
    // glTF: at least 1, or exactly 0 (the extensions' "Fresnel 1").
    const float v = number(*ior, "ior", 1.5f, values, what + " KHR_materials_ior");
    m.ior = v == 0.0f ? 0.0f : values.clamped(v, 1.0f, 1e6f, what + " KHR_materials_ior ior");
  }
  if (const auto* spec = extension(gm, "KHR_materials_specular")) {
    const std::string where = what + " KHR_materials_specular";
    m.specularFactor = values.clamped(number(*spec, "specularFactor", 1.0f, values, where), 0.0f, 1.0f, where + " specularFactor");
    // The colour may exceed 1 (F0 is clamped to 1 after the texture multiplies it).
    m.specularColorFactor = numbers<3>(*spec, "specularColorFactor", glm::vec3(1.0f), 0.0f, 1e6f, values, where);
    m.specularTexture = texture(extensionTexture(*spec, "specularTexture", values, where), false, where + " specularTexture");
    m.specularColorTexture =
        texture(extensionTexture(*spec, "specularColorTexture", values, where), true, where + " specularColorTexture");
  }
  m.unlit = extension(gm, "KHR_materials_unlit") != nullptr;
  if (const auto* tr = extension(gm, "KHR_materials_transmission")) {
    const std::string where = what + " KHR_materials_transmission";
    m.transmission = values.clamped(number(*tr, "transmissionFactor", 0.0f, values, where), 0.0f, 1.0f,
                                    where + " transmissionFactor");
    m.transmissionTexture =
        texture(extensionTexture(*tr, "transmissionTexture", values, where), false, where + " transmissionTexture");
  }
  if (const auto* cc = extension(gm, "KHR_materials_clearcoat")) {
    const std::string where = what + " KHR_materials_clearcoat";
    m.clearcoat =
        values.clamped(number(*cc, "clearcoatFactor", 0.0f, values, where), 0.0f, 1.0f, where + " clearcoatFactor");
    m.clearcoatRoughness = values.clamped(number(*cc, "clearcoatRoughnessFactor", 0.0f, values, where), 0.0f, 1.0f,
                                          where + " clearcoatRoughnessFactor");
    m.clearcoatTexturesUnread =
        cc->Has("clearcoatTexture") || cc->Has("clearcoatRoughnessTexture") || cc->Has("clearcoatNormalTexture");
  }
  if (const auto* vol = extension(gm, "KHR_materials_volume")) {
    const std::string where = what + " KHR_materials_volume";
    m.thickness =
        values.clamped(number(*vol, "thicknessFactor", 0.0f, values, where), 0.0f, 1e30f, where + " thicknessFactor");
    m.attenuationColor = numbers<3>(*vol, "attenuationColor", glm::vec3(1.0f), 0.0f, 1.0f, values, where);
    // glTF: positive, infinite when absent (no absorption).
    const float distance = number(*vol, "attenuationDistance", std::numeric_limits<float>::infinity(), values, where);
    if (!(distance > 0.0f)) values.fail(fmt::format("{} attenuationDistance {} is not positive", where, distance));
    m.attenuationDistance = distance;
  }
}

SpecularGlossinessConversion metalRoughFromSpecularGlossiness(glm::vec3 diffuse, glm::vec3 specular) {
  // The conversion Khronos's sample code uses: the metallic that best explains the specular's
  // brightness next to the diffuse's, then the base colour from the diffuse (dielectric part)
  // and from the specular (metal part), blended by metallic^2.
  constexpr float d = 0.04f;  // the dielectric F0 of the metal-rough model
  auto perceived = [](glm::vec3 c) { return std::sqrt(0.299f * c.r * c.r + 0.587f * c.g * c.g + 0.114f * c.b * c.b); };
  const float oneMinusSpecular = 1.0f - std::max({specular.r, specular.g, specular.b});
  const float pd = perceived(diffuse), ps = perceived(specular);
  float metallic = 0.0f;
  if (ps >= d) {
    const float b = pd * oneMinusSpecular / (1.0f - d) + ps - 2.0f * d, c = d - ps;
    const float discriminant = std::max(b * b - 4.0f * d * c, 0.0f);
    metallic = std::clamp((-b + std::sqrt(discriminant)) / (2.0f * d), 0.0f, 1.0f);
  }
  const glm::vec3 fromDiffuse = diffuse * (oneMinusSpecular / (1.0f - d) / std::max(1.0f - metallic, 1e-4f));
  const glm::vec3 fromSpecular = (specular - glm::vec3(d * (1.0f - metallic))) / std::max(metallic, 1e-4f);
  SpecularGlossinessConversion out;
  out.metallic = metallic;
  out.baseColor = glm::clamp(glm::mix(fromDiffuse, fromSpecular, metallic * metallic), 0.0f, 1.0f);
  // What each model makes of it (glTF's reference shading): F0 and the diffuse colour.
  const glm::vec3 f0 = glm::mix(glm::vec3(d), out.baseColor, metallic);
  const glm::vec3 diffuseColor = out.baseColor * (1.0f - d) * (1.0f - metallic);
  const glm::vec3 e0 = glm::abs(f0 - specular), e1 = glm::abs(diffuseColor - diffuse * oneMinusSpecular);
  out.error = std::max({e0.r, e0.g, e0.b, e1.r, e1.g, e1.b});
  return out;
}

void readSpecularGlossiness(const tinygltf::Material& gm, Material& m, ImportValues& values, const std::string& what,
                            const TextureReader& texture, const Scene& scene) {
  const auto* sg = extension(gm, "KHR_materials_pbrSpecularGlossiness");
  if (!sg) return;
  const std::string where = what + " KHR_materials_pbrSpecularGlossiness";
  const glm::vec4 diffuseFactor = numbers<4>(*sg, "diffuseFactor", glm::vec4(1.0f), 0.0f, 1.0f, values, where);
  const glm::vec3 specularFactor = numbers<3>(*sg, "specularFactor", glm::vec3(1.0f), 0.0f, 1.0f, values, where);
  const float glossinessFactor =
      values.clamped(number(*sg, "glossinessFactor", 1.0f, values, where), 0.0f, 1.0f, where + " glossinessFactor");
  auto average = [&](const std::optional<TextureRef>& t) {
    return t && t->texture < scene.textures.size() ? textureAverage(scene.textures[t->texture]) : glm::vec4(1.0f);
  };
  // The diffuse image stays the base colour's texture; the specular-glossiness image has no
  // metal-rough counterpart, so its mean (linear rgb, glossiness in a) enters the factors.
  m.baseColorTexture = texture(extensionTexture(*sg, "diffuseTexture", values, where), true, where + " diffuseTexture");
  const auto specularGlossiness = texture(extensionTexture(*sg, "specularGlossinessTexture", values, where), true,
                                          where + " specularGlossinessTexture");
  const glm::vec4 diffuseMean = average(m.baseColorTexture), sgMean = average(specularGlossiness);
  const glm::vec3 diffuse = glm::vec3(diffuseFactor) * glm::vec3(diffuseMean);
  const auto converted = metalRoughFromSpecularGlossiness(diffuse, specularFactor * glm::vec3(sgMean));
  // base = factor x texture, so the factor is the converted colour over the texture's mean.
  for (int c = 0; c < 3; ++c)
    m.baseColorFactor[c] = diffuseMean[c] > 0.0f ? std::min(converted.baseColor[c] / diffuseMean[c], 1.0f) : 0.0f;
  m.baseColorFactor.a = diffuseFactor.a;
  m.metallic = converted.metallic;
  m.roughness = 1.0f - glossinessFactor * sgMean.a;
  m.metallicRoughnessTexture.reset();
  m.specularGlossinessError = converted.error;
  m.specularGlossinessTextureUnread = specularGlossiness.has_value();
}

}  // namespace tl::scene
