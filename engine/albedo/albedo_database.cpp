#include "albedo/albedo_database.h"

#include "scene/input_limits.h"

#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

namespace tl::albedo {
namespace {

// The schema, one step per version: migrate() applies the steps a file lacks, in one
// transaction with the new user_version, so a killed migration leaves the old schema.
const char* const kMigrations[] = {
    // 0 -> 1: baked entries and overrides in separate tables.
    "CREATE TABLE meta(name TEXT PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE baked(key TEXT PRIMARY KEY, r REAL NOT NULL, g REAL NOT NULL, b REAL NOT NULL,"
    " coverage REAL NOT NULL, view_coverage TEXT NOT NULL, view_variance REAL NOT NULL,"
    " baker_version INTEGER NOT NULL, baked_at TEXT NOT NULL);"
    "CREATE TABLE overrides(key TEXT PRIMARY KEY, r REAL NOT NULL, g REAL NOT NULL, b REAL NOT NULL,"
    " edited_at TEXT NOT NULL);",
    // 1 -> 2: labels, so the Albedo panel can name entries the current scene no longer has,
    // and a revision counter for captures.
    "ALTER TABLE baked ADD COLUMN label TEXT NOT NULL DEFAULT '';"
    "ALTER TABLE overrides ADD COLUMN label TEXT NOT NULL DEFAULT '';"
    "INSERT OR IGNORE INTO meta(name, value) VALUES('revision', '0');",
};
static_assert(std::size(kMigrations) == AlbedoDatabase::kSchemaVersion);

class Statement {
 public:
  Statement(sqlite3* db, const char* sql, const std::filesystem::path& file) : db_(db), file_(file) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      throw DatabaseError(fmt::format("{}: {}", file.string(), sqlite3_errmsg(db)));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& text(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& real(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  Statement& integer(int i, int64_t v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  // True while there is a row.
  bool step() {
    int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw DatabaseError(fmt::format("{}: {}", file_.string(), sqlite3_errmsg(db_)));
  }
  void run() {
    step();
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::string columnText(int i) const {
    const unsigned char* t = sqlite3_column_text(stmt_, i);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  double columnReal(int i) const { return sqlite3_column_double(stmt_, i); }
  int64_t columnInt(int i) const { return sqlite3_column_int64(stmt_, i); }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  const std::filesystem::path& file_;
};

// BEGIN IMMEDIATE ... COMMIT; rolled back when an exception leaves the scope.
class Transaction {
 public:
  explicit Transaction(sqlite3* db) : db_(db) { sqlite3_exec(db_, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr); }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit(const std::filesystem::path& file) {
    if (sqlite3_exec(db_, "COMMIT", nullptr, nullptr, nullptr) != SQLITE_OK)
      throw DatabaseError(fmt::format("{}: commit failed: {}", file.string(), sqlite3_errmsg(db_)));
    done_ = true;
  }

 private:
  sqlite3* db_;
  bool done_ = false;
};

std::string joinCoverage(const std::array<float, kViews>& c) {
  std::string s;
  for (int i = 0; i < kViews; ++i) s += fmt::format("{}{:.9g}", i ? "," : "", c[i]);
  return s;
}

std::array<float, kViews> splitCoverage(const std::string& s) {
  std::array<float, kViews> c{};
  std::istringstream in(s);
  std::string item;
  for (int i = 0; i < kViews && std::getline(in, item, ','); ++i) c[i] = std::strtof(item.c_str(), nullptr);
  return c;
}

BakedEntry readBaked(const Statement& q) {
  BakedEntry e;
  e.key = keyFromHex(q.columnText(0)).value_or(0);
  e.rgb = glm::vec3(q.columnReal(1), q.columnReal(2), q.columnReal(3));
  e.coverage = float(q.columnReal(4));
  e.viewCoverage = splitCoverage(q.columnText(5));
  e.viewVariance = float(q.columnReal(6));
  e.bakerVersion = uint32_t(q.columnInt(7));
  e.bakedAt = q.columnText(8);
  e.label = q.columnText(9);
  return e;
}

constexpr const char* kInsertBaked =
    "INSERT OR REPLACE INTO baked(key, r, g, b, coverage, view_coverage, view_variance, baker_version, baked_at, label)"
    " VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)";
constexpr const char* kInsertOverride =
    "INSERT OR REPLACE INTO overrides(key, r, g, b, edited_at, label) VALUES(?1, ?2, ?3, ?4, ?5, ?6)";

void insertBaked(Statement& q, const BakedEntry& e) {
  q.text(1, keyToHex(e.key)).real(2, e.rgb.r).real(3, e.rgb.g).real(4, e.rgb.b).real(5, e.coverage);
  q.text(6, joinCoverage(e.viewCoverage)).real(7, e.viewVariance).integer(8, e.bakerVersion);
  q.text(9, e.bakedAt).text(10, e.label).run();
}

void insertOverride(Statement& q, const OverrideEntry& e) {
  q.text(1, keyToHex(e.key)).real(2, e.rgb.r).real(3, e.rgb.g).real(4, e.rgb.b).text(5, e.editedAt).text(6, e.label).run();
}

constexpr const char* kSelectBaked =
    "SELECT key, r, g, b, coverage, view_coverage, view_variance, baker_version, baked_at, label FROM baked";

bool sameColour(const glm::vec3& a, const glm::vec3& b) { return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(1e-6f))); }

// What the first bytes of a file say it is, before SQLite sees it (SQLite would happily
// treat some foreign files as an empty database on first write).
void checkHeader(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw DatabaseError(fmt::format("{}: cannot be read", file.string()));
  char header[16] = {};
  in.read(header, sizeof header);
  if (in.gcount() == 0) return;  // empty: a database created but never written (SQLite's own rule)
  if (in.gcount() < 16 || std::memcmp(header, "SQLite format 3", 16) != 0)
    throw DatabaseError(fmt::format("{}: not an albedo database (not an SQLite file); left untouched", file.string()));
}

}  // namespace

std::string utcNow() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

AlbedoDatabase::AlbedoDatabase(const std::filesystem::path& file, bool create) : file_(file) {
  // Before anything opens it: a FIFO would block both the header check and SQLite forever,
  // a device would be read (or written) as if it were a database.
  try {
    scene::requireRegularFile(file, true);
  } catch (const scene::InputFileError& e) {
    throw DatabaseError(fmt::format("{}; left untouched", e.what()));
  }
  const bool exists = std::filesystem::exists(file);
  if (!exists && !create) throw DatabaseError(fmt::format("{}: no such albedo database", file.string()));
  if (exists) checkHeader(file);
  int flags = SQLITE_OPEN_READWRITE | (exists ? 0 : SQLITE_OPEN_CREATE);
  if (sqlite3_open_v2(file.string().c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw DatabaseError(fmt::format("{}: cannot open: {}", file.string(), why));
  }
  sqlite3_busy_timeout(db_, 5000);
  try {
    // Verify before anything could write: a damaged page fails here, not halfway through a bake.
    Statement check(db_, "PRAGMA quick_check", file_);
    std::string verdict = check.step() ? check.columnText(0) : "no answer";
    if (verdict != "ok") throw DatabaseError(fmt::format("{}: damaged database ({}); left untouched", file.string(), verdict));
    Statement app(db_, "PRAGMA application_id", file_);
    const int64_t id = app.step() ? app.columnInt(0) : 0;
    Statement tables(db_, "SELECT count(*) FROM sqlite_master", file_);
    const int64_t tableCount = tables.step() ? tables.columnInt(0) : 0;
    if (id != kApplicationId && (id != 0 || tableCount != 0))
      throw DatabaseError(fmt::format("{}: an SQLite database of another application, not an albedo database; left untouched",
                                      file.string()));
    // SQLite's user_version is any 32-bit integer; only 0..kSchemaVersion have migrations (a
    // negative one indexed kMigrations[-1], found by fuzz_albedo_db).
    if (schemaVersion() < 0)
      throw DatabaseError(fmt::format("{}: schema {}, which no Twinlight writes: not an albedo database; left untouched",
                                      file.string(), schemaVersion()));
    if (schemaVersion() > kSchemaVersion)
      throw DatabaseError(fmt::format("{}: written by a newer Twinlight (schema {}, this one reads up to {}); left untouched",
                                      file.string(), schemaVersion(), kSchemaVersion));
    exec("PRAGMA synchronous = FULL");
    migrate();
  } catch (const DatabaseError&) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

AlbedoDatabase::~AlbedoDatabase() { sqlite3_close(db_); }

void AlbedoDatabase::exec(const char* sql) const {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    std::string why = error ? error : "unknown error";
    sqlite3_free(error);
    throw DatabaseError(fmt::format("{}: {}", file_.string(), why));
  }
}

int AlbedoDatabase::schemaVersion() const {
  Statement q(db_, "PRAGMA user_version", file_);
  return q.step() ? int(q.columnInt(0)) : 0;
}

void AlbedoDatabase::migrate() {
  const int from = schemaVersion();
  if (from == kSchemaVersion) return;
  Transaction t(db_);
  exec(fmt::format("PRAGMA application_id = {}", kApplicationId).c_str());
  for (int v = from; v < kSchemaVersion; ++v) exec(kMigrations[v]);
  exec(fmt::format("PRAGMA user_version = {}", kSchemaVersion).c_str());
  t.commit(file_);
}

uint64_t AlbedoDatabase::revision() const {
  Statement q(db_, "SELECT value FROM meta WHERE name = 'revision'", file_);
  return q.step() ? std::strtoull(q.columnText(0).c_str(), nullptr, 10) : 0;
}

void AlbedoDatabase::bumpRevision() {
  exec("UPDATE meta SET value = CAST(CAST(value AS INTEGER) + 1 AS TEXT) WHERE name = 'revision'");
}

std::map<AlbedoKey, BakedEntry> AlbedoDatabase::baked() const {
  std::map<AlbedoKey, BakedEntry> out;
  Statement q(db_, kSelectBaked, file_);
  while (q.step()) {
    BakedEntry e = readBaked(q);
    out[e.key] = std::move(e);
  }
  return out;
}

std::optional<BakedEntry> AlbedoDatabase::findBaked(AlbedoKey key) const {
  Statement q(db_, fmt::format("{} WHERE key = ?1", kSelectBaked).c_str(), file_);
  q.text(1, keyToHex(key));
  if (!q.step()) return std::nullopt;
  return readBaked(q);
}

bool AlbedoDatabase::hasBaked(AlbedoKey key) const {
  Statement q(db_, "SELECT 1 FROM baked WHERE key = ?1", file_);
  q.text(1, keyToHex(key));
  return q.step();
}

std::map<AlbedoKey, OverrideEntry> AlbedoDatabase::overrides() const {
  std::map<AlbedoKey, OverrideEntry> out;
  Statement q(db_, "SELECT key, r, g, b, edited_at, label FROM overrides", file_);
  while (q.step()) {
    OverrideEntry e;
    e.key = keyFromHex(q.columnText(0)).value_or(0);
    e.rgb = glm::vec3(q.columnReal(1), q.columnReal(2), q.columnReal(3));
    e.editedAt = q.columnText(4);
    e.label = q.columnText(5);
    out[e.key] = std::move(e);
  }
  return out;
}

void AlbedoDatabase::writeBaked(const std::vector<BakedEntry>& entries, const std::function<void()>& beforeCommit) {
  if (entries.empty()) return;
  Transaction t(db_);
  Statement q(db_, kInsertBaked, file_);
  for (const BakedEntry& e : entries) insertBaked(q, e);
  bumpRevision();
  if (beforeCommit) beforeCommit();
  t.commit(file_);
}

void AlbedoDatabase::writeOverrides(const std::vector<OverrideEntry>& set, const std::vector<AlbedoKey>& clear) {
  if (set.empty() && clear.empty()) return;
  Transaction t(db_);
  Statement put(db_, kInsertOverride, file_);
  for (const OverrideEntry& e : set) insertOverride(put, e);
  Statement drop(db_, "DELETE FROM overrides WHERE key = ?1", file_);
  for (AlbedoKey k : clear) drop.text(1, keyToHex(k)).run();
  bumpRevision();
  t.commit(file_);
}

MergeReport AlbedoDatabase::mergeFrom(const AlbedoDatabase& other) {
  MergeReport report;
  std::map<AlbedoKey, BakedEntry> mine = baked();
  std::vector<BakedEntry> addBaked;
  for (auto& [key, theirs] : other.baked()) {
    auto it = mine.find(key);
    if (it == mine.end()) {
      addBaked.push_back(theirs);
      ++report.bakedAdded;
    } else if (sameColour(it->second.rgb, theirs.rgb) && it->second.bakerVersion == theirs.bakerVersion) {
      ++report.bakedSame;
    } else {
      report.conflicts.push_back(fmt::format("baked {} ({}): ({:.4f}, {:.4f}, {:.4f}) here vs ({:.4f}, {:.4f}, {:.4f}) in {}: kept this one",
                                             keyToHex(key), theirs.label, it->second.rgb.r, it->second.rgb.g, it->second.rgb.b,
                                             theirs.rgb.r, theirs.rgb.g, theirs.rgb.b, other.file().string()));
    }
  }
  std::map<AlbedoKey, OverrideEntry> myOverrides = overrides();
  std::vector<OverrideEntry> setOverrides;
  for (auto& [key, theirs] : other.overrides()) {
    auto it = myOverrides.find(key);
    if (it == myOverrides.end()) {
      setOverrides.push_back(theirs);
      ++report.overridesAdded;
    } else if (sameColour(it->second.rgb, theirs.rgb)) {
      ++report.overridesSame;
    } else {
      const bool theirsLater = theirs.editedAt > it->second.editedAt;
      report.conflicts.push_back(fmt::format("override {} ({}): ({:.4f}, {:.4f}, {:.4f}) edited {} here vs ({:.4f}, {:.4f}, {:.4f}) edited {} in {}: kept the {}",
                                             keyToHex(key), theirs.label, it->second.rgb.r, it->second.rgb.g, it->second.rgb.b,
                                             it->second.editedAt, theirs.rgb.r, theirs.rgb.g, theirs.rgb.b, theirs.editedAt,
                                             other.file().string(), theirsLater ? "later one from there" : "one here"));
      if (theirsLater) setOverrides.push_back(theirs);
    }
  }
  Transaction t(db_);
  Statement q(db_, kInsertBaked, file_);
  for (const BakedEntry& e : addBaked) insertBaked(q, e);
  Statement put(db_, kInsertOverride, file_);
  for (const OverrideEntry& e : setOverrides) insertOverride(put, e);
  bumpRevision();
  t.commit(file_);
  return report;
}

}  // namespace tl::albedo
