// Per-instance albedo for one scene: override > baked > texture average, resolved for every
// mesh + material combination (each instance resolves through its combination's key), with
// artist edits held in memory — undoable, then saved to the database in one transaction.
#pragma once

#include "albedo/albedo_database.h"
#include "albedo/albedo_key.h"

#include <memory>
#include <optional>
#include <vector>

namespace tl::albedo {

enum class AlbedoSource : uint8_t { Override, Baked, TextureAverage };
const char* sourceName(AlbedoSource source);  // "override", "baked", "texture average"

struct AlbedoEntry {
  Combination combination;
  glm::vec3 textureAverage{0.0f};     // always computed: the fallback
  std::optional<BakedEntry> baked;
  std::optional<glm::vec3> override;  // including unsaved edits
  bool stale = false;    // not baked, but the database holds rows for this label under another key
  glm::vec3 resolved{0.0f};
  AlbedoSource source = AlbedoSource::TextureAverage;
};

class AlbedoLibrary {
 public:
  AlbedoLibrary(const scene::Scene& scene, const BakeSettings& settings = {});

  // Attaches a database (or none) and reloads baked rows and overrides; unsaved edits and
  // the undo history are dropped.
  void attach(std::unique_ptr<AlbedoDatabase> db);
  AlbedoDatabase* database() { return db_.get(); }
  const AlbedoDatabase* database() const { return db_.get(); }
  void reload();  // after a bake wrote to the database

  const std::vector<AlbedoEntry>& entries() const { return entries_; }
  uint32_t combinationOf(uint32_t instance) const { return instanceCombination_.at(instance); }
  const AlbedoEntry& entryOf(uint32_t instance) const { return entries_.at(combinationOf(instance)); }
  // Per scene instance: rgb resolved, w the source (shared/albedo.h kAlbedoSource*);
  // `version` changes whenever any value does.
  const std::vector<glm::vec4>& instanceAlbedo() const { return instanceAlbedo_; }
  uint64_t version() const { return version_; }

  // Edits. `merge`: fold into the previous edit of the same combination (one undo step for
  // a colour-picker drag).
  void setOverride(uint32_t combination, const glm::vec3& rgb, bool merge = false);
  void clearOverride(uint32_t combination);
  bool undo();
  bool redo();
  bool canUndo() const { return undoCount_ > 0; }
  bool canRedo() const { return undoCount_ < edits_.size(); }
  bool unsaved() const { return savedAt_ != undoCount_ || savedAtInvalid_; }
  // Writes the overrides that differ from the database in one transaction. Throws
  // DatabaseError (and keeps the edits) when there is no database or the write fails.
  void save();

 private:
  struct Edit {
    uint32_t combination;
    std::optional<glm::vec3> before, after;
  };
  void apply(uint32_t combination, const std::optional<glm::vec3>& value);
  void push(Edit edit, bool merge);
  void resolve();

  std::unique_ptr<AlbedoDatabase> db_;
  std::vector<AlbedoEntry> entries_;
  std::vector<uint32_t> instanceCombination_;
  std::vector<glm::vec4> instanceAlbedo_;
  std::vector<Edit> edits_;
  size_t undoCount_ = 0;     // edits_[0, undoCount_) are applied
  size_t savedAt_ = 0;       // undoCount_ when last saved or loaded
  bool savedAtInvalid_ = false;
  uint64_t version_ = 1;
};

}  // namespace tl::albedo
