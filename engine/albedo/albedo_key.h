// Albedo keys: one content hash (xxHash64) per distinct mesh + material combination, of
// exactly what decides its baked albedo — triangle positions and UVs, the base colour and
// metallic inputs (factors and texture texels), alpha testing — and the bake settings. Never
// names or paths: a renamed file or node keeps its key; editing any hashed value changes it.
#pragma once

#include "scene/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tl::albedo {

// Bumped when the baker's output for the same input changes; part of every key, so a new
// baker re-bakes everything and old rows show as stale instead of being trusted.
inline constexpr uint32_t kBakerVersion = 1;

struct BakeSettings {
  uint32_t tileSize = 64;  // pixels per side of each of the 6 orthographic views
  bool operator==(const BakeSettings&) const = default;
};

using AlbedoKey = uint64_t;

std::string keyToHex(AlbedoKey key);                           // 16 lower-case hex digits
std::optional<AlbedoKey> keyFromHex(std::string_view text);    // nothing unless exactly that

// The key of scene mesh `mesh` with its material.
AlbedoKey albedoKey(const scene::Scene& scene, uint32_t mesh, const BakeSettings& settings);

// One distinct key of a scene: the first mesh that has it (what the baker renders), a label
// for people ("mesh / material"), and every instance that resolves through it.
struct Combination {
  AlbedoKey key = 0;
  uint32_t mesh = 0;
  std::string label;
  std::vector<uint32_t> instances;
};

struct SceneKeys {
  std::vector<Combination> combinations;  // sorted by key: a deterministic order for shards
  std::vector<uint32_t> instanceCombination;  // per scene instance: index into combinations
};

SceneKeys sceneKeys(const scene::Scene& scene, const BakeSettings& settings);

// Shard i of n (0-based) owns the keys whose high 32 bits % n == i: stable whatever else the
// content set holds, so shards baked on different machines never overlap and cover everything.
// Not key % n: a key's atlas slot is key % 42 (AlbedoBaker::bakeSlot), and a shard count that
// shares a factor with 42 would then fill only some slots of every batch (4 shards: half of
// them, 42 shards: one key a batch). The hash's high half is independent of key % 42.
inline bool inShard(AlbedoKey key, uint32_t index, uint32_t count) {
  return count <= 1 || uint32_t(key >> 32) % count == index;
}

}  // namespace tl::albedo
