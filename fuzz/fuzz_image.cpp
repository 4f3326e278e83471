// libFuzzer target: texture decoding (scene/scene_internal.h decodeImage): PNG, JPEG,
// OpenEXR and Radiance HDR through OpenImageIO from memory, dimensions and channels checked before pixels are
// allocated. A false return is a refusal; anything else is a finding.
#include "scene/scene_internal.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tl::scene::Texture texture;
  std::string error;
  if (tl::scene::decodeImage(std::vector<uint8_t>(data, data + size), texture, error) &&
      (texture.format == tl::scene::TexelFormat::Rgba8 ? texture.rgba8.size() : texture.rgba16.size()) !=
          size_t(texture.width) * texture.height * 4)
    __builtin_trap();  // a decoded texture must hold exactly its texels
  return 0;
}
