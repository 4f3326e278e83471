// The features of a glTF file Twinlight does not render (or renders approximately), counted
// and reported as one warning each (Scene::ignored).
#include "scene/gltf_parts.h"

namespace tl::scene {

void IgnoredFeatures::add(const std::string& feature, const std::string& instead) {
  for (auto& e : entries_)
    if (e.feature == feature) return void(++e.count);
  entries_.push_back({feature, instead, 1});
}

void IgnoredFeatures::report(Scene& scene, const std::filesystem::path& file) const {
  for (const auto& e : entries_) {
    std::string line = fmt::format("{} ({}x): {}", e.feature, e.count, e.instead);
    scene.warnings.push_back(fmt::format("{}: {}", file.string(), line));
    scene.ignored.push_back(std::move(line));
  }
}

void scanIgnored(const tinygltf::Model& model, IgnoredFeatures& ignored) {
  for (const auto& e : model.extensionsUsed)
    if (!extensionApplied(e)) ignored.add("extension " + e, "not applied (the file renders as if it were absent)");
  for (const auto& m : model.materials) {
    forEachTextureSlot(m, [&](const char* slot, int index, int texCoord, const tinygltf::ExtensionMap& extensions) {
      if (index < 0) return;
      if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end() && it->second.Has("texCoord") &&
                                                               it->second.Get("texCoord").IsInt())
        texCoord = it->second.Get("texCoord").GetNumberAsInt();
      if (texCoord > 1) ignored.add(fmt::format("TEXCOORD_{} in a {}", texCoord, slot), "sampled with TEXCOORD_0");
    });
  }
  for (const auto& mesh : model.meshes)
    for (const auto& p : mesh.primitives) {
      if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) ignored.add("points, lines and strips", "primitives skipped");
      if (p.attributes.count("JOINTS_1") || p.attributes.count("WEIGHTS_1"))
        ignored.add("more than four joints per vertex (JOINTS_1/WEIGHTS_1)", "the first four are used, their weights renormalised");
      if (p.attributes.count("JOINTS_0") != p.attributes.count("WEIGHTS_0"))
        ignored.add("JOINTS_0 without WEIGHTS_0 (or the other way)", "drawn as stored");
      for (const auto& target : p.targets)
        if (target.count("TANGENT")) ignored.add("morph target TANGENT deltas", "tangents keep their rest pose");
    }
  for (const auto& a : model.animations)
    for (const auto& ch : a.channels)
      if (ch.target_path != "weights" && ch.target_path != "translation" && ch.target_path != "rotation" &&
          ch.target_path != "scale")
        ignored.add(fmt::format("node {} animation", ch.target_path), "not played (morph weights and node TRS are)");
  if (model.scenes.size() > 1) ignored.add("scenes besides the default", "not loaded");
}

}  // namespace tl::scene
