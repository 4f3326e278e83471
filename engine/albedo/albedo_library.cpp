#include "albedo/albedo_library.h"

#include "scene/material_average.h"
#include "shared/albedo.h"

#include <map>

namespace tl::albedo {

const char* sourceName(AlbedoSource source) {
  switch (source) {
    case AlbedoSource::Override: return "override";
    case AlbedoSource::Baked: return "baked";
    case AlbedoSource::TextureAverage: return "texture average";
  }
  return "?";
}

AlbedoLibrary::AlbedoLibrary(const scene::Scene& scene, const BakeSettings& settings) {
  SceneKeys keys = sceneKeys(scene, settings);
  instanceCombination_ = std::move(keys.instanceCombination);
  // Once per material: a texture average touches every texel, and many meshes share one.
  std::vector<glm::vec3> materialAverage;
  for (const scene::Material& m : scene.materials) materialAverage.push_back(scene::materialAverageAlbedo(scene, m));
  for (Combination& c : keys.combinations) {
    AlbedoEntry e;
    const scene::Mesh& mesh = scene.meshes.at(c.mesh);
    e.textureAverage = materialAverage.at(std::min<size_t>(mesh.material, scene.materials.size() - 1));
    e.combination = std::move(c);
    entries_.push_back(std::move(e));
  }
  resolve();
}

void AlbedoLibrary::attach(std::unique_ptr<AlbedoDatabase> db) {
  db_ = std::move(db);
  edits_.clear();
  undoCount_ = savedAt_ = 0;
  savedAtInvalid_ = false;
  for (AlbedoEntry& e : entries_) e.override.reset();
  reload();
}

void AlbedoLibrary::reload() {
  std::map<AlbedoKey, BakedEntry> baked;
  std::map<AlbedoKey, OverrideEntry> overrides;
  if (db_) baked = db_->baked(), overrides = db_->overrides();
  std::multimap<std::string, AlbedoKey> keyOfLabel;
  for (auto& [key, row] : baked) keyOfLabel.emplace(row.label, key);
  for (auto& [key, row] : overrides) keyOfLabel.emplace(row.label, key);
  for (size_t i = 0; i < entries_.size(); ++i) {
    AlbedoEntry& e = entries_[i];
    const AlbedoKey key = e.combination.key;
    auto b = baked.find(key);
    e.baked = b == baked.end() ? std::nullopt : std::optional<BakedEntry>(b->second);
    // Unsaved edits win over what the database says; otherwise its override.
    bool edited = false;
    for (size_t k = 0; k < undoCount_; ++k) edited |= edits_[k].combination == i;
    if (!edited) {
      auto o = overrides.find(key);
      e.override = o == overrides.end() ? std::nullopt : std::optional<glm::vec3>(o->second.rgb);
    }
    // Stale: nothing baked for this key, but rows for the same label under another key
    // (the mesh or material was edited after the bake; an old override may need redoing).
    e.stale = false;
    auto [lo, hi] = keyOfLabel.equal_range(e.combination.label);
    for (auto it = lo; it != hi; ++it) e.stale |= !e.baked && it->second != key;
  }
  resolve();
}

void AlbedoLibrary::resolve() {
  for (AlbedoEntry& e : entries_) {
    if (e.override) e.resolved = *e.override, e.source = AlbedoSource::Override;
    else if (e.baked) e.resolved = e.baked->rgb, e.source = AlbedoSource::Baked;
    else e.resolved = e.textureAverage, e.source = AlbedoSource::TextureAverage;
  }
  instanceAlbedo_.resize(instanceCombination_.size());
  for (size_t i = 0; i < instanceCombination_.size(); ++i) {
    const AlbedoEntry& e = entries_[instanceCombination_[i]];
    const float code = e.source == AlbedoSource::Override ? shared::kAlbedoSourceOverride
                       : e.source == AlbedoSource::Baked  ? shared::kAlbedoSourceBaked
                                                          : shared::kAlbedoSourceTextureAverage;
    instanceAlbedo_[i] = glm::vec4(e.resolved, code);
  }
  ++version_;
}

void AlbedoLibrary::apply(uint32_t combination, const std::optional<glm::vec3>& value) {
  entries_.at(combination).override = value;
  resolve();
}

void AlbedoLibrary::push(Edit edit, bool merge) {
  edits_.resize(undoCount_);  // a new edit drops what could be redone
  if (savedAt_ > undoCount_) savedAtInvalid_ = true;
  if (merge && !edits_.empty() && undoCount_ != savedAt_ && edits_.back().combination == edit.combination) {
    edits_.back().after = edit.after;
  } else {
    edits_.push_back(edit);
    ++undoCount_;
  }
  apply(edit.combination, edit.after);
}

void AlbedoLibrary::setOverride(uint32_t combination, const glm::vec3& rgb, bool merge) {
  push({combination, entries_.at(combination).override, glm::clamp(rgb, 0.0f, 1.0f)}, merge);
}

void AlbedoLibrary::clearOverride(uint32_t combination) {
  if (!entries_.at(combination).override) return;
  push({combination, entries_[combination].override, std::nullopt}, false);
}

bool AlbedoLibrary::undo() {
  if (!canUndo()) return false;
  --undoCount_;
  apply(edits_[undoCount_].combination, edits_[undoCount_].before);
  return true;
}

bool AlbedoLibrary::redo() {
  if (!canRedo()) return false;
  apply(edits_[undoCount_].combination, edits_[undoCount_].after);
  ++undoCount_;
  return true;
}

void AlbedoLibrary::save() {
  if (!db_) throw DatabaseError("no albedo database is open: open or create one to save overrides");
  std::map<AlbedoKey, OverrideEntry> stored = db_->overrides();
  std::vector<OverrideEntry> set;
  std::vector<AlbedoKey> clear;
  const std::string now = utcNow();
  for (const AlbedoEntry& e : entries_) {
    auto it = stored.find(e.combination.key);
    if (e.override && (it == stored.end() || it->second.rgb != *e.override))
      set.push_back({e.combination.key, *e.override, now, e.combination.label});
    else if (!e.override && it != stored.end())
      clear.push_back(e.combination.key);
  }
  db_->writeOverrides(set, clear);
  savedAt_ = undoCount_;
  savedAtInvalid_ = false;
}

}  // namespace tl::albedo
