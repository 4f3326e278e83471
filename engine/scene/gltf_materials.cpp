// glTF materials: the metallic-roughness factors and textures (with KHR_texture_transform),
// emission (KHR_materials_emissive_strength), alpha, normal and occlusion maps, every value
// checked as the float it is stored in (ImportValues); the extensions that change the
// reflection, and specular-glossiness's conversion, in gltf_material_extensions.cpp.
#include "scene/gltf_parts.h"

#include <algorithm>

namespace tl::scene {
namespace {

// A material's textureInfo: its texture (through the cache), UV set and KHR_texture_transform
// (whose texCoord overrides the textureInfo's, as the extension says). UV sets beyond
// TEXCOORD_1 read TEXCOORD_0 (IgnoredFeatures says so).
std::optional<TextureRef> textureRef(TextureCache& textures, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                                     bool srgb, ImportValues& values, const std::string& what) {
  const auto texture = textures.get(index, srgb);
  if (!texture) return std::nullopt;
  TextureRef r;
  r.texture = *texture;
  if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
    const auto& t = it->second;
    auto pair = [&](const char* name, glm::vec2& out) {
      if (!t.Has(name)) return;
      const auto& v = t.Get(name);
      if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
        values.fail(fmt::format("{} KHR_texture_transform {} is not two numbers", what, name));
      for (int c = 0; c < 2; ++c) out[c] = values.finite(v.Get(c).GetNumberAsDouble(), fmt::format("{} KHR_texture_transform {}", what, name));
    };
    pair("offset", r.offset);
    pair("scale", r.scale);
    if (t.Has("rotation")) {
      if (!t.Get("rotation").IsNumber()) values.fail(what + " KHR_texture_transform rotation is not a number");
      r.rotation = values.finite(t.Get("rotation").GetNumberAsDouble(), what + " KHR_texture_transform rotation");
    }
    if (t.Has("texCoord") && t.Get("texCoord").IsInt()) texCoord = t.Get("texCoord").GetNumberAsInt();
  }
  r.texCoord = texCoord == 1 ? 1u : 0u;
  return r;
}

}  // namespace

void readMaterials(GltfImport& in, TextureCache& textures) {
  ImportValues& values = in.values;
  for (size_t i = 0; i < in.model.materials.size(); ++i) {
    const auto& gm = in.model.materials[i];
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name.empty() ? fmt::format("material{}", i) : gm.name;
    const std::string what = fmt::format("material `{}`", m.name);
    // The glTF ranges: factors in [0, 1] (an albedo above 1 creates energy), emission >= 0.
    if (pbr.baseColorFactor.size() == 4)
      for (int c = 0; c < 4; ++c) m.baseColorFactor[c] = values.clamped(pbr.baseColorFactor[size_t(c)], 0.0f, 1.0f, what + " baseColorFactor");
    else if (!pbr.baseColorFactor.empty()) values.fail(what + " baseColorFactor does not have 4 components");
    m.metallic = values.clamped(pbr.metallicFactor, 0.0f, 1.0f, what + " metallicFactor");
    m.roughness = values.clamped(pbr.roughnessFactor, 0.0f, 1.0f, what + " roughnessFactor");
    m.emissiveFactor = values.lightColor(gm.emissiveFactor, m.emissiveFactor, what + " emissiveFactor");
    if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end()) {
      const auto& s = it->second.Get("emissiveStrength");
      if (s.IsNumber()) m.emissiveStrength = values.light(s.GetNumberAsDouble(), what + " emissiveStrength");
    }
    values.requireLightRange(m.emissiveFactor * m.emissiveStrength, what + " emission (emissiveFactor x emissiveStrength)");
    m.normalScale = values.finite(gm.normalTexture.scale, what + " normalTexture.scale");
    m.alphaMode = gm.alphaMode == "MASK" ? AlphaMode::Mask : gm.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alphaCutoff = values.clamped(gm.alphaCutoff, 0.0f, 1.0f, what + " alphaCutoff");
    m.doubleSided = gm.doubleSided;
    m.baseColorTexture = textureRef(textures, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                    pbr.baseColorTexture.extensions, true, values, what + " baseColorTexture");
    m.metallicRoughnessTexture =
        textureRef(textures, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                   pbr.metallicRoughnessTexture.extensions, false, values, what + " metallicRoughnessTexture");
    m.normalTexture = textureRef(textures, gm.normalTexture.index, gm.normalTexture.texCoord, gm.normalTexture.extensions,
                                 false, values, what + " normalTexture");
    m.emissiveTexture = textureRef(textures, gm.emissiveTexture.index, gm.emissiveTexture.texCoord,
                                   gm.emissiveTexture.extensions, true, values, what + " emissiveTexture");
    m.occlusionTexture = textureRef(textures, gm.occlusionTexture.index, gm.occlusionTexture.texCoord,
                                    gm.occlusionTexture.extensions, false, values, what + " occlusionTexture");
    m.occlusionStrength = values.clamped(gm.occlusionTexture.strength, 0.0f, 1.0f, what + " occlusionTexture.strength");
    const TextureReader texture = [&](const ExtensionTexture& t, bool srgb, const std::string& slot) {
      return textureRef(textures, t.index, t.texCoord, t.extensions, srgb, values, slot);
    };
    readReflectionExtensions(gm, m, values, what, texture);
    readSpecularGlossiness(gm, m, values, what, texture, in.scene);
    in.scene.materials.push_back(std::move(m));
  }
  // What the conversions and the G-buffer leave approximate, once per feature with its count.
  float worst = 0.0f;
  for (const auto& m : in.scene.materials) worst = std::max(worst, m.specularGlossinessError);
  for (const auto& m : in.scene.materials) {
    if (m.specularGlossinessError >= 0.0f)
      in.ignored.add("KHR_materials_pbrSpecularGlossiness",
                     fmt::format("converted to metal-rough (F0 and diffuse colour within {:.3f} of the file's)", worst));
    if (m.specularGlossinessTextureUnread)
      in.ignored.add("specularGlossinessTexture", "its mean enters the converted factors (the diffuse texture is kept)");
    const glm::vec3 c = m.specularColorFactor;
    if (m.specularColorTexture || c.r != c.g || c.g != c.b)
      in.ignored.add("a tinted KHR_materials_specular colour", "in the reference; the G-buffer paths use its luminance");
    if (m.transmits())
      in.ignored.add(
          "KHR_materials_transmission",
          "in the reference (a thin surface unrefracted); stochastic coverage (grey, at normal incidence) in the "
          "G-buffer paths");
    if (m.clearcoat > 0.0f && !m.unlit)
      in.ignored.add("KHR_materials_clearcoat",
                     "in the reference; the G-buffer paths render the base without its coat");
    if (m.clearcoatTexturesUnread)
      in.ignored.add("KHR_materials_clearcoat textures",
                     "not read (the coat's factors hold across the surface, its normal is the base's)");
    if (m.transmits() && m.thickness > 0.0f)
      in.ignored.add("KHR_materials_volume", "refraction and absorption in the reference only");
  }
}

void addDefaultMaterial(Scene& scene) {
  Material m;
  m.name = "default";
  m.metallic = 0.0f;
  m.roughness = 0.8f;
  m.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  scene.materials.push_back(m);
}

}  // namespace tl::scene
