#include "scene/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace tl::scene {
namespace {

const char* sourceName(ImageSource s) {
  switch (s) {
    case ImageSource::File: return "file";
    case ImageSource::DataUri: return "data URI";
    case ImageSource::BufferView: return "bufferView";
    case ImageSource::Generated: return "generated";
  }
  return "?";
}

std::string formatName(const Texture& t) {
  std::string bits = t.fileBits == 8 ? "8-bit" : t.fileBits == 16 ? "16-bit" : fmt::format("{}-bit float", t.fileBits);
  if (t.fileBits == 16 && t.fileFormat == "openexr") bits = "16-bit float";
  const char* gpu = t.format == TexelFormat::Rgba8 ? (t.srgb ? "RGBA8 sRGB" : "RGBA8")
                    : t.format == TexelFormat::Rgba16Unorm ? "RGBA16" : "RGBA16F";
  return fmt::format("{} {} ({}) -> {}", t.fileFormat.empty() ? "image" : t.fileFormat, bits, sourceName(t.source), gpu);
}

// "3 a, 1 b" from counts in first-seen order.
std::string counts(const std::vector<std::pair<std::string, size_t>>& c) {
  std::string out;
  for (const auto& [what, n] : c) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", n, what);
  return out;
}

void count(std::vector<std::pair<std::string, size_t>>& c, const std::string& what) {
  for (auto& [w, n] : c)
    if (w == what) return void(++n);
  c.emplace_back(what, 1);
}

// How each extension the importer knows is rendered (docs/user-guide.md "What of glTF 2.0
// renders"); what is still approximated is also a line of Scene::ignored.
std::string extensionRendering(const std::string& name) {
  static const std::pair<const char*, const char*> kRendered[] = {
      {"KHR_materials_emissive_strength", "rendered: emission scaled in every path and the reference"},
      {"KHR_materials_ior", "rendered: the dielectric's F0 in the shared BRDF, every path and the reference"},
      {"KHR_materials_specular",
       "rendered: the dielectric's F0 and F90 in the shared BRDF, every path and the reference (a tinted colour in "
       "grey in the "
       "G-buffer paths)"},
      {"KHR_materials_unlit", "rendered: the base colour as emission over a black, non-reflecting surface"},
      {"KHR_materials_transmission",
       "rendered: light through the surface, tinted and by Fresnel, in the reference (a thin surface unrefracted); the "
       "G-buffer paths draw it as stochastic coverage (grey, at normal incidence)"},
      {"KHR_materials_clearcoat",
       "rendered: a clear coat over the base (albedo-scaled, energy-conserving) in the reference; the G-buffer paths "
       "render "
       "the base alone"},
      {"KHR_materials_volume",
       "rendered: refraction and Beer-Lambert absorption inside the mesh in the reference; the G-buffer paths draw it "
       "as a "
       "thin transmitting surface"},
      {"KHR_materials_pbrSpecularGlossiness", "converted to metal-rough on import (the error is an ignored line)"},
      {"KHR_lights_punctual", "rendered: point, spot and directional lights in their photometric units"},
      {"KHR_mesh_quantization", "read: integer and normalized attributes"},
      {"KHR_texture_transform", "rendered: in every stage that samples a texture"},
  };
  for (const auto& [extension, how] : kRendered)
    if (name == extension) return how;
  return "ignored (the file renders as if it were absent)";
}

}  // namespace

std::vector<std::string> sceneReport(const Scene& s) {
  std::vector<std::string> lines;
  size_t triangles = 0, deforming = 0, generatedTangents = 0;
  for (const auto& m : s.meshes) {
    triangles += m.indices.size() / 3;
    deforming += m.deforms();
    generatedTangents += m.generatedTangents;
  }
  lines.push_back(fmt::format("meshes: {} ({} triangles, {} with morph targets, {} with generated tangents), instances: {}",
                              s.meshes.size(), triangles, deforming, generatedTangents, s.instances.size()));
  std::vector<std::pair<std::string, size_t>> modes;
  for (const auto& m : s.materials)
    count(modes, m.alphaMode == AlphaMode::Mask ? "alpha MASK" : m.alphaMode == AlphaMode::Blend ? "alpha BLEND" : "opaque");
  // Glass is counted beside the alpha modes: a transmitting surface has one of them too.
  size_t transmitting = 0, volumes = 0;
  for (const auto& m : s.materials) {
    transmitting += m.transmits();
    volumes += m.transmits() && m.thickness > 0.0f;
  }
  std::string glass =
      transmitting ? fmt::format("; {} transmitting, {} of them bounding a volume", transmitting, volumes) : "";
  lines.push_back(fmt::format("materials: {} ({}{})", s.materials.size(), counts(modes), glass));
  std::vector<std::pair<std::string, size_t>> formats;
  size_t placeholders = 0;
  for (const auto& t : s.textures) {
    count(formats, formatName(t));
    placeholders += t.placeholder;
  }
  lines.push_back(fmt::format("textures: {}{}{}", s.textures.size(), formats.empty() ? "" : " (" + counts(formats) + ")",
                              placeholders ? fmt::format(", {} missing (magenta placeholder)", placeholders) : ""));
  std::vector<std::pair<std::string, size_t>> lights;
  for (const auto& l : s.lights)
    count(lights, l.type == LightType::Directional ? "directional" : l.type == LightType::Spot ? "spot"
                  : l.type == LightType::Point     ? "point"
                                                   : "area");
  lines.push_back(fmt::format("lights: {}{}", s.lights.size(), lights.empty() ? "" : " (" + counts(lights) + ")"));
  const auto orthographic = std::count_if(s.cameras.begin(), s.cameras.end(), [](const Camera& c) { return c.orthographic; });
  lines.push_back(fmt::format("cameras: {} perspective, {} orthographic", s.cameras.size() - size_t(orthographic), orthographic));
  lines.push_back(fmt::format("animations: {} morph-weight channels, {} node channels (translation, rotation, scale), {:.3g} s",
                              s.morphAnimations.size(), s.nodeAnimations.size(), s.animationSeconds));
  size_t joints = 0, skinnedMeshes = 0;
  for (const auto& skin : s.skins) joints += skin.joints.size();
  for (const auto& m : s.meshes) skinnedMeshes += m.skinned();
  lines.push_back(fmt::format("skins: {} ({} joints, {} skinned meshes)", s.skins.size(), joints, skinnedMeshes));
  if (s.extensionsUsed.empty()) lines.push_back("extensions: none");
  for (const auto& e : s.extensionsUsed) lines.push_back(fmt::format("extension {}: {}", e, extensionRendering(e)));
  for (const auto& i : s.ignored) lines.push_back("ignored: " + i);
  if (s.ignored.empty()) lines.push_back("ignored: nothing");
  return lines;
}

}  // namespace tl::scene
