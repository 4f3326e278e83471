// The albedo database: one SQLite file with baked entries and artist overrides in separate
// tables, keyed by albedo key (albedo_key.h). Every write is one transaction, so a process
// killed at any moment leaves the last committed state; a file that is not ours, or is
// damaged, or is from a newer schema, is refused with one clear error and never modified.
#pragma once

#include "albedo/albedo_key.h"

#include <glm/glm.hpp>

#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

struct sqlite3;

namespace tl::albedo {

struct DatabaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The six orthographic views in order: from +X, -X, +Y, -Y, +Z, -Z (object space).
inline constexpr int kViews = 6;

struct BakedEntry {
  AlbedoKey key = 0;
  glm::vec3 rgb{0.0f};                // linear hit albedo: visible average through the F0 rule
  float coverage = 0.0f;              // mean over the views of the covered fraction of each view
  std::array<float, kViews> viewCoverage{};
  float viewVariance = 0.0f;          // coverage-weighted variance of the views' mean albedo (mean of RGB)
  uint32_t bakerVersion = kBakerVersion;
  std::string bakedAt;                // UTC, ISO 8601
  std::string label;                  // "mesh / material" when baked (for people; not part of the key)
};

struct OverrideEntry {
  AlbedoKey key = 0;
  glm::vec3 rgb{0.0f};
  std::string editedAt;
  std::string label;
};

struct MergeReport {
  uint32_t bakedAdded = 0, bakedSame = 0, overridesAdded = 0, overridesSame = 0;
  std::vector<std::string> conflicts;  // one line each: key, both values, which was kept
};

class AlbedoDatabase {
 public:
  static constexpr int kSchemaVersion = 2;
  static constexpr int kApplicationId = 0x544C4142;  // "TLAB"

  // Opens `file`, creating it when it does not exist and `create` is set, and migrates an
  // older schema. Throws DatabaseError naming the file and the reason otherwise.
  explicit AlbedoDatabase(const std::filesystem::path& file, bool create = true);
  ~AlbedoDatabase();
  AlbedoDatabase(const AlbedoDatabase&) = delete;
  AlbedoDatabase& operator=(const AlbedoDatabase&) = delete;

  const std::filesystem::path& file() const { return file_; }
  int schemaVersion() const;
  // Counts committed write transactions: what a capture records as the database's version.
  uint64_t revision() const;

  std::map<AlbedoKey, BakedEntry> baked() const;
  std::map<AlbedoKey, OverrideEntry> overrides() const;
  std::optional<BakedEntry> findBaked(AlbedoKey key) const;
  bool hasBaked(AlbedoKey key) const;

  // One transaction each. Existing rows with the same key are replaced.
  // `beforeCommit` (crash tests) runs inside the transaction after the rows are written.
  void writeBaked(const std::vector<BakedEntry>& entries, const std::function<void()>& beforeCommit = {});
  // Sets `set` and removes `clear`, together.
  void writeOverrides(const std::vector<OverrideEntry>& set, const std::vector<AlbedoKey>& clear);

  // Adds another database's rows in one transaction. Equal rows count as the same; a baked
  // conflict keeps this database's row, an override conflict keeps the later edit; every
  // conflict is reported. Overrides are never dropped.
  MergeReport mergeFrom(const AlbedoDatabase& other);

 private:
  void exec(const char* sql) const;
  void migrate();
  void bumpRevision();
  std::filesystem::path file_;
  sqlite3* db_ = nullptr;
};

std::string utcNow();

}  // namespace tl::albedo
