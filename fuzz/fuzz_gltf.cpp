// libFuzzer target: the glTF / GLB importer from bytes (scene/scene_internal.h loadGltfBytes),
// with every limit of scene/input_limits.h in force. The scene "lives" in a private folder
// holding the content's buffers and textures, so seeds from content/ resolve their files.
// A SceneError is the importer refusing the input: fine. Anything else -- a crash, a
// sanitizer report, another exception, an allocation past libFuzzer's limit -- is a finding.
#include "fuzz_folder.h"
#include "scene/scene_internal.h"

#include <cstring>

static std::filesystem::path gFolder;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  gFolder = tl::fuzz::privateFolder("gltf");
  const std::filesystem::path content(TWINLIGHT_CONTENT_DIR);
  for (const auto& entry : std::filesystem::directory_iterator(content))
    if (entry.path().extension() == ".bin") std::filesystem::copy_file(entry.path(), gFolder / entry.path().filename());
  std::filesystem::copy(content / "textures", gFolder / "textures");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  try {
    tl::scene::loadGltfBytes(std::vector<uint8_t>(data, data + size), binary, gFolder / (binary ? "fuzz.glb" : "fuzz.gltf"),
                             {});
  } catch (const tl::scene::SceneError&) {
  }
  return 0;
}
