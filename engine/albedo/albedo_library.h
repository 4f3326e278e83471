// Per-instance albedo for one scene: override > baked > texture average, resolved for every
// mesh + material combination (each instance resolves through its combination's key), with
// artist edits held in memory — undoable, then saved to the database in one transaction.
#pragma once

#include "albedo/albedo_database.h"
#include "albedo/albedo_key.h"

#include <map>
#include <memory>
#include <string>
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

// An artist's override whose mesh + material key is in none of the scene's combinations:
// the mesh or material content changed since the edit (its label still names a combination
// of the scene, `sameLabel`), or it is not in this scene (removed, renamed and changed, or
// the database is shared with another scene). Held until it is re-applied to a combination
// or deleted; never dropped on its own: saving keeps it in the database.
struct OrphanOverride {
  AlbedoKey key = 0;
  glm::vec3 rgb{0.0f};                // the colour that no longer reaches any hit
  std::string label;                  // "mesh / material" when it was edited
  std::string editedAt;               // UTC; empty for an edit never saved
  std::optional<uint32_t> sameLabel;  // the scene's combination with that label now
  bool inDatabase = false;            // the database holds it as it is here
  bool removed = false;               // re-applied or deleted: the database drops it on save
};
// One line for people: why the override reaches nothing now.
std::string orphanReason(const OrphanOverride& orphan);

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
  bool unsaved() const;
  // When the edit an undo or a redo would act on was made (steady-clock seconds), so that an
  // editor with several histories undoes the latest edit first and redoes in reverse.
  std::optional<double> undoTime() const;
  std::optional<double> redoTime() const;

  // Orphaned overrides (OrphanOverride): the database's, plus unsaved edits carried over a
  // scene reload by keepOrphan. Entries stay in place (indices are stable until attach);
  // re-applied or deleted ones are marked `removed`.
  const std::vector<OrphanOverride>& orphans() const { return orphans_; }
  size_t orphanCount() const;  // those not removed
  // An override for `key` that the new scene has no combination for (an unsaved edit
  // before a reload): held as an orphan, saved with the rest.
  void keepOrphan(AlbedoKey key, const glm::vec3& rgb, const std::string& label);
  // Moves the orphan's colour onto `combination` (its override) and removes the orphan:
  // one undo step.
  void reapplyOrphan(size_t orphan, uint32_t combination);
  void deleteOrphan(size_t orphan);  // one undo step; the database drops it on save
  // Writes the overrides that differ from the database in one transaction. Throws
  // DatabaseError (and keeps the edits) when there is no database or the write fails.
  void save();

 private:
  // An override change of a combination, an orphan removed (re-applied or deleted), or both.
  struct Edit {
    std::optional<uint32_t> combination;
    std::optional<glm::vec3> before, after;
    std::optional<size_t> orphan;
    double madeAt = 0.0;  // steady-clock seconds of its last change
  };
  void step(const Edit& edit, bool forward);
  void findOrphans(const std::map<AlbedoKey, OverrideEntry>& overrides);
  void apply(uint32_t combination, const std::optional<glm::vec3>& value);
  void push(Edit edit, bool merge);
  void resolve();

  std::unique_ptr<AlbedoDatabase> db_;
  std::vector<AlbedoEntry> entries_;
  std::vector<uint32_t> instanceCombination_;
  std::vector<glm::vec4> instanceAlbedo_;
  std::vector<Edit> edits_;
  std::vector<OrphanOverride> orphans_;
  size_t undoCount_ = 0;     // edits_[0, undoCount_) are applied
  size_t savedAt_ = 0;       // undoCount_ when last saved or loaded
  bool savedAtInvalid_ = false;
  uint64_t version_ = 1;
};

}  // namespace tl::albedo
