#include "albedo/albedo_library.h"

#include "scene/material_average.h"
#include "shared/albedo.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
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

std::string orphanReason(const OrphanOverride& orphan) {
  if (orphan.sameLabel)
    return "its mesh or material changed since the edit (positions, UVs, base colour, metallic or alpha: the key "
           "hashes them), so the override reaches no hit";
  return "no mesh + material of this scene is called that or has its key: removed, renamed and changed, or "
         "edited in another scene that shares this database";
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
  orphans_.clear();
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
    // An entry any edit of the history touched holds what the history's position says, applied
    // or undone (an undo after a save leaves the colour before the saved one, which the database
    // no longer holds); the others take the database's override.
    bool edited = false;
    for (const Edit& edit : edits_) edited |= edit.combination == i;
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
  findOrphans(overrides);
  resolve();
}

void AlbedoLibrary::findOrphans(const std::map<AlbedoKey, OverrideEntry>& overrides) {
  std::map<AlbedoKey, uint32_t> ours;
  std::map<std::string, uint32_t> byLabel;
  for (uint32_t c = 0; c < entries_.size(); ++c) {
    ours.emplace(entries_[c].combination.key, c);
    byLabel.emplace(entries_[c].combination.label, c);
  }
  // Existing orphans keep their place (edits refer to them by index); the database's new
  // ones are added after them.
  for (OrphanOverride& o : orphans_) o.inDatabase = false;
  for (const auto& [key, row] : overrides) {
    if (ours.count(key)) continue;
    // Captured by name: clang 14 (the fuzz presets) cannot capture a structured binding.
    auto it = std::find_if(orphans_.begin(), orphans_.end(), [&key = key](const OrphanOverride& o) { return o.key == key; });
    if (it == orphans_.end()) {
      OrphanOverride o;
      o.key = key, o.rgb = row.rgb, o.label = row.label, o.editedAt = row.editedAt;
      it = orphans_.insert(orphans_.end(), o);
    }
    it->inDatabase = it->rgb == row.rgb;
    if (it->inDatabase) it->editedAt = row.editedAt;
  }
  for (OrphanOverride& o : orphans_) {
    auto l = byLabel.find(o.label);
    o.sameLabel = l == byLabel.end() ? std::nullopt : std::optional<uint32_t>(l->second);
  }
}

size_t AlbedoLibrary::orphanCount() const {
  return size_t(std::count_if(orphans_.begin(), orphans_.end(), [](const OrphanOverride& o) { return !o.removed; }));
}

void AlbedoLibrary::keepOrphan(AlbedoKey key, const glm::vec3& rgb, const std::string& label) {
  for (const AlbedoEntry& e : entries_)
    if (e.combination.key == key) return;  // not an orphan here
  auto it = std::find_if(orphans_.begin(), orphans_.end(), [&key = key](const OrphanOverride& o) { return o.key == key; });
  if (it == orphans_.end()) {
    OrphanOverride o;
    o.key = key, o.label = label;
    it = orphans_.insert(orphans_.end(), o);
    for (uint32_t c = 0; c < entries_.size(); ++c)
      if (entries_[c].combination.label == label) it->sameLabel = c;
  }
  if (it->rgb != rgb || !it->inDatabase) it->rgb = rgb, it->inDatabase = false, it->editedAt.clear();
  it->removed = false;
}

void AlbedoLibrary::reapplyOrphan(size_t orphan, uint32_t combination) {
  if (orphans_.at(orphan).removed) return;
  push({combination, entries_.at(combination).override, orphans_[orphan].rgb, orphan}, false);
}

void AlbedoLibrary::deleteOrphan(size_t orphan) {
  if (orphans_.at(orphan).removed) return;
  push({std::nullopt, std::nullopt, std::nullopt, orphan}, false);
}

bool AlbedoLibrary::unsaved() const {
  if (savedAt_ != undoCount_ || savedAtInvalid_) return true;
  // An orphan carried over a reload that the database does not hold yet.
  return std::any_of(orphans_.begin(), orphans_.end(), [](const OrphanOverride& o) { return !o.removed && !o.inDatabase; });
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

void AlbedoLibrary::step(const Edit& edit, bool forward) {
  if (edit.orphan) orphans_.at(*edit.orphan).removed = forward;
  if (edit.combination) apply(*edit.combination, forward ? edit.after : edit.before);
}

std::optional<double> AlbedoLibrary::undoTime() const {
  return canUndo() ? std::optional<double>(edits_[undoCount_ - 1].madeAt) : std::nullopt;
}

std::optional<double> AlbedoLibrary::redoTime() const {
  return canRedo() ? std::optional<double>(edits_[undoCount_].madeAt) : std::nullopt;
}

void AlbedoLibrary::push(Edit edit, bool merge) {
  edit.madeAt = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  edits_.resize(undoCount_);  // a new edit drops what could be redone
  if (savedAt_ > undoCount_) savedAtInvalid_ = true;
  if (merge && !edit.orphan && !edits_.empty() && undoCount_ != savedAt_ && !edits_.back().orphan &&
      edits_.back().combination == edit.combination) {
    edits_.back().after = edit.after;
    edits_.back().madeAt = edit.madeAt;
  } else {
    edits_.push_back(edit);
    ++undoCount_;
  }
  step(edit, true);
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
  step(edits_[undoCount_], false);
  return true;
}

bool AlbedoLibrary::redo() {
  if (!canRedo()) return false;
  step(edits_[undoCount_], true);
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
  // Orphans stay in the database until re-applied or deleted; one carried over a reload
  // is written so that it outlives the session.
  for (const OrphanOverride& o : orphans_) {
    const bool inStore = stored.count(o.key) != 0;
    if (o.removed && inStore) clear.push_back(o.key);
    else if (!o.removed && !o.inDatabase) set.push_back({o.key, o.rgb, now, o.label});
  }
  db_->writeOverrides(set, clear);
  for (OrphanOverride& o : orphans_) {
    o.inDatabase = !o.removed;
    if (!o.removed && o.editedAt.empty()) o.editedAt = now;
  }
  savedAt_ = undoCount_;
  savedAtInvalid_ = false;
}

}  // namespace tl::albedo
