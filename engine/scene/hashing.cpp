// Content hashes (xxHash64). They hash what a thing *is* — texels, vertex data, parameter
// values — never names or paths, so renaming a file changes nothing and editing a texture
// changes exactly the materials that use it.
#include "scene/scene_internal.h"

#include <xxhash.h>

namespace tl::scene {
namespace {

struct Hasher {
  XXH64_state_t* state = XXH64_createState();
  Hasher() { XXH64_reset(state, 0); }
  ~Hasher() { XXH64_freeState(state); }
  template <class T>
  void add(const T& v) { XXH64_update(state, &v, sizeof(T)); }
  void bytes(const void* p, size_t n) { XXH64_update(state, p, n); }
  uint64_t done() const { return XXH64_digest(state); }
};

}  // namespace

uint64_t hashBytes(const void* data, size_t size, uint64_t seed) { return XXH64(data, size, seed); }

uint64_t hashTexels(const Texture& t) {
  Hasher h;
  h.add(t.width);
  h.add(t.height);
  // 8-bit textures hash as they always did (width, height, texels), so albedo keys stay.
  if (t.format == TexelFormat::Rgba8) {
    h.bytes(t.rgba8.data(), t.rgba8.size());
  } else {
    h.add(t.format);
    h.bytes(t.rgba16.data(), t.rgba16.size() * sizeof(uint16_t));
  }
  return h.done();
}

uint64_t hashMesh(const Mesh& m) {
  Hasher h;
  uint64_t nv = m.vertices.size(), ni = m.indices.size();
  h.add(nv);
  h.bytes(m.vertices.data(), m.vertices.size() * sizeof(Vertex));
  h.add(ni);
  h.bytes(m.indices.data(), m.indices.size() * sizeof(uint32_t));
  return h.done();
}

uint64_t hashMaterial(const Material& m, const std::vector<Texture>& textures) {
  Hasher h;
  h.add(m.baseColorFactor);
  h.add(m.metallic);
  h.add(m.roughness);
  h.add(m.emissiveFactor);
  h.add(m.emissiveStrength);
  h.add(m.normalScale);
  h.add(m.alphaMode);
  h.add(m.alphaCutoff);
  uint8_t doubleSided = m.doubleSided;
  h.add(doubleSided);
  h.add(m.occlusionStrength);
  h.add(m.ior);
  h.add(m.specularFactor);
  h.add(m.specularColorFactor);
  uint8_t unlit = m.unlit;
  h.add(unlit);
  h.add(m.transmission);
  h.add(m.thickness);
  h.add(m.attenuationColor);
  h.add(m.attenuationDistance);
  h.add(m.clearcoat);
  h.add(m.clearcoatRoughness);
  for (const auto& t : {m.baseColorTexture, m.normalTexture, m.metallicRoughnessTexture, m.emissiveTexture,
                        m.occlusionTexture, m.specularTexture, m.specularColorTexture, m.transmissionTexture}) {
    uint64_t th = t && t->texture < textures.size() ? textures[t->texture].contentHash : 0;
    h.add(th);
    if (!t) continue;
    h.add(t->texCoord);
    h.add(t->offset);
    h.add(t->rotation);
    h.add(t->scale);
    if (t->texture < textures.size()) h.add(textures[t->texture].sampler);
  }
  return h.done();
}

uint64_t hashScene(const Scene& s) {
  Hasher h;
  for (const auto& m : s.meshes) h.add(m.contentHash);
  for (const auto& m : s.materials) h.add(m.contentHash);
  for (const auto& i : s.instances) {
    h.add(i.mesh);
    h.add(i.transform);
  }
  // What plays: a scene whose door swings otherwise is another scene.
  for (const auto& a : s.nodeAnimations) {
    h.add(a.node);
    h.add(a.property);
    h.add(a.interpolation);
    for (float t : a.times) h.add(t);
    for (const auto& v : a.values) h.add(v);
  }
  h.add(s.environment.sunDirection);
  h.add(s.environment.sunIrradiance);
  h.add(s.environment.skyRadiance);
  for (const auto& l : s.lights) {
    h.add(l.type);
    h.add(l.color);
    h.add(l.intensity);
    float range = l.range.value_or(0.0f);
    h.add(range);
    h.add(l.innerConeAngle);
    h.add(l.outerConeAngle);
    h.add(l.position);
    h.add(l.direction);
  }
  return h.done();
}

}  // namespace tl::scene
