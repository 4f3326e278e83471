#include "albedo/albedo_key.h"

#include <fmt/format.h>
#include <xxhash.h>

#include <algorithm>
#include <map>

namespace tl::albedo {
namespace {

// Streams little-endian values into XXH64. Floats are canonicalised (-0 -> +0) so values
// that compare equal hash equal.
class KeyHasher {
 public:
  KeyHasher() { XXH64_reset(state_, 0); }
  ~KeyHasher() { XXH64_freeState(state_); }
  KeyHasher(const KeyHasher&) = delete;
  KeyHasher& operator=(const KeyHasher&) = delete;

  void u32(uint32_t v) { XXH64_update(state_, &v, sizeof v); }
  void u64(uint64_t v) { XXH64_update(state_, &v, sizeof v); }
  void f32(float v) {
    v = v + 0.0f;
    XXH64_update(state_, &v, sizeof v);
  }
  void text(std::string_view s) {
    u64(s.size());
    XXH64_update(state_, s.data(), s.size());
  }
  // A texture the bake samples. Its UV set, transform and sampler enter only where they are
  // not glTF's defaults, so keys of files without them stay what they were.
  void texture(const scene::Scene& scene, const std::optional<scene::TextureRef>& ref) {
    if (!ref || ref->texture >= scene.textures.size()) return u32(0);
    const scene::Texture& t = scene.textures[ref->texture];
    u32(1);
    u64(t.contentHash);  // width, height and texels
    u32(t.srgb ? 1 : 0);
    if (*ref != scene::TextureRef{ref->texture}) {
      u32(ref->texCoord);
      f32(ref->offset.x), f32(ref->offset.y), f32(ref->rotation), f32(ref->scale.x), f32(ref->scale.y);
    }
    if (t.sampler != scene::SamplerMode{})
      u32(uint32_t(t.sampler.wrapS) | uint32_t(t.sampler.wrapT) << 4 | uint32_t(t.sampler.magNearest) << 8 |
          uint32_t(t.sampler.minNearest) << 9 | uint32_t(t.sampler.mipNearest) << 10 | uint32_t(t.sampler.noMipmaps) << 11);
  }
  uint64_t digest() const { return XXH64_digest(state_); }

 private:
  XXH64_state_t* state_ = XXH64_createState();
};

}  // namespace

std::string keyToHex(AlbedoKey key) { return fmt::format("{:016x}", key); }

std::optional<AlbedoKey> keyFromHex(std::string_view text) {
  if (text.size() != 16) return std::nullopt;
  AlbedoKey key = 0;
  for (char c : text) {
    int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (digit < 0) return std::nullopt;
    key = key << 4 | AlbedoKey(digit);
  }
  return key;
}

AlbedoKey albedoKey(const scene::Scene& scene, uint32_t meshIndex, const BakeSettings& settings) {
  const scene::Mesh& mesh = scene.meshes.at(meshIndex);
  KeyHasher h;
  h.text("twinlight.albedo");
  h.u32(kBakerVersion);
  h.u32(settings.tileSize);

  // Geometry: what the orthographic views rasterise and where they sample textures.
  h.u64(mesh.vertices.size());
  for (const scene::Vertex& v : mesh.vertices) {
    h.f32(v.position.x), h.f32(v.position.y), h.f32(v.position.z);
    h.f32(v.uv.x), h.f32(v.uv.y);
  }
  // The second UV set and vertex colours, only where a file has them (the keys of files
  // without stay what they were).
  const bool uv1 = std::any_of(mesh.vertices.begin(), mesh.vertices.end(), [](const scene::Vertex& v) { return v.uv1 != glm::vec2(0.0f); });
  const bool colour = std::any_of(mesh.vertices.begin(), mesh.vertices.end(), [](const scene::Vertex& v) { return v.color != glm::vec4(1.0f); });
  if (uv1 || colour) {
    h.text("uv1+color");
    for (const scene::Vertex& v : mesh.vertices) {
      h.f32(v.uv1.x), h.f32(v.uv1.y);
      for (int c = 0; c < 4; ++c) h.f32(v.color[c]);
    }
  }
  h.u64(mesh.indices.size());
  for (uint32_t i : mesh.indices) h.u32(i);

  // Material: base colour and metallic (the F0 rule), and alpha testing (coverage).
  const scene::Material& m = scene.materials.at(std::min<size_t>(mesh.material, scene.materials.size() - 1));
  for (int c = 0; c < 4; ++c) h.f32(m.baseColorFactor[c]);
  h.f32(m.metallic);
  h.texture(scene, m.baseColorTexture);
  h.texture(scene, m.metallicRoughnessTexture);
  // Coverage: MASK cuts below its cutoff; BLEND covers wherever alpha is above 0.
  h.u32(uint32_t(m.alphaMode));
  if (m.alphaMode == scene::AlphaMode::Mask) h.f32(m.alphaCutoff);
  return h.digest();
}

SceneKeys sceneKeys(const scene::Scene& scene, const BakeSettings& settings) {
  std::vector<AlbedoKey> meshKey(scene.meshes.size());
  std::map<AlbedoKey, Combination> byKey;
  for (uint32_t i = 0; i < scene.meshes.size(); ++i) {
    meshKey[i] = albedoKey(scene, i, settings);
    auto [it, added] = byKey.try_emplace(meshKey[i]);
    if (added) {
      const scene::Mesh& mesh = scene.meshes[i];
      it->second.key = meshKey[i];
      it->second.mesh = i;
      it->second.label = mesh.name + " / " + scene.materials.at(std::min<size_t>(mesh.material, scene.materials.size() - 1)).name;
    }
  }
  SceneKeys out;
  std::map<AlbedoKey, uint32_t> index;
  for (auto& [key, c] : byKey) {
    index[key] = uint32_t(out.combinations.size());
    out.combinations.push_back(std::move(c));
  }
  out.instanceCombination.resize(scene.instances.size());
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    uint32_t c = index.at(meshKey.at(scene.instances[i].mesh));
    out.instanceCombination[i] = c;
    out.combinations[c].instances.push_back(i);
  }
  return out;
}

}  // namespace tl::albedo
