// glTF 2.0 import with tinygltf, by concern (gltf_parts.h): the file read and parsed under
// the limits of scene/input_limits.h (gltf_file.cpp), then materials, meshes, skins, the node
// hierarchy, animations and lights, each in its own file. Every accessor read is bounds-checked
// with overflow-safe arithmetic (gltf_reader.h), and every number is checked after conversion
// to float (scene/import_values.h): tinygltf validates neither, and a malformed file must
// produce one clear error, never a crash.
#include "scene/gltf_parts.h"

namespace tl::scene {

Scene loadGltfBytes(std::vector<uint8_t> bytes, bool binary, const std::filesystem::path& file, const LoadOptions& options) {
  const tinygltf::Model model = parseGltf(std::move(bytes), binary, file, options);
  GltfReader rd(model, file);
  Scene scene;
  scene.name = file.stem().string();
  scene.path = file;
  ImportValues values(file, scene.warnings);
  scene.extensionsUsed = model.extensionsUsed;
  IgnoredFeatures ignored;
  scanIgnored(model, ignored);
  GltfImport in{model, rd, values, ignored, scene, file};

  // Textures: one entry per (glTF texture, colour space) actually used by a material.
  TextureCache textures(model, file, options, scene);
  readMaterials(in, textures);
  const uint32_t defaultMaterial = uint32_t(scene.materials.size());
  bool usedDefault = false;
  const std::vector<std::vector<uint32_t>> meshPrimitives = readMeshes(in, defaultMaterial, usedDefault);
  if (usedDefault || scene.materials.empty()) addDefaultMaterial(scene);
  for (auto& m : scene.materials) m.contentHash = hashMaterial(m, scene.textures);

  readSkins(in);
  const size_t sceneIndex = readNodes(in, meshPrimitives);
  readAnimations(in);
  readEnvironment(in, sceneIndex);

  ignored.report(scene, file);
  scene.contentHash = hashScene(scene);
  return scene;
}

}  // namespace tl::scene
