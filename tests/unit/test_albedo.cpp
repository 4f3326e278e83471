// Albedo keys, the database and per-instance resolution: pure logic, no GPU.
#include "albedo/albedo_baker.h"
#include "albedo/albedo_database.h"
#include "albedo/albedo_library.h"
#include "scene/material_average.h"
#include "../common/test_scenes.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <sqlite3.h>

namespace tl::albedo {
namespace {

namespace fs = std::filesystem;

scene::Material plainMaterial(glm::vec3 colour = glm::vec3(0.5f), float metallic = 0.0f) {
  scene::Material m;
  m.name = "paint";
  m.baseColorFactor = glm::vec4(colour, 1.0f);
  m.metallic = metallic;
  return m;
}

AlbedoKey cubeKey(const scene::Scene& s, const BakeSettings& settings = {}) { return albedoKey(s, 0, settings); }

// A fresh path under the test temp dir, with nothing there.
fs::path tempFile(const std::string& name) {
  fs::path p = fs::path(::testing::TempDir()) / ("twinlight_albedo_" + name);
  fs::remove(p);
  fs::remove(fs::path(p.string() + "-journal"));
  return p;
}

std::string fileBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AlbedoKey, HexRoundTripsAndRejectsAnythingElse) {
  EXPECT_EQ(keyToHex(0x0123456789abcdefull), "0123456789abcdef");
  EXPECT_EQ(keyFromHex("0123456789abcdef"), 0x0123456789abcdefull);
  EXPECT_FALSE(keyFromHex("0123456789ABCDEF"));
  EXPECT_FALSE(keyFromHex("0123"));
  EXPECT_FALSE(keyFromHex("0123456789abcdeg"));
}

// The same content gives the same key on every run and machine: a known answer pins it
// (a change here invalidates every database in the field, so it must be deliberate).
TEST(AlbedoKey, KnownAnswerForAKnownCube) {
  auto s = test::makeCubeScene(plainMaterial());
  EXPECT_EQ(keyToHex(cubeKey(*s)), "6815b4d2c787ced5");
}

TEST(AlbedoKey, ChangesWithEverythingItHashes) {
  auto base = test::makeCubeScene(plainMaterial());
  const AlbedoKey k = cubeKey(*base);
  auto changed = [&](auto&& edit) {
    auto s = test::makeCubeScene(plainMaterial());
    edit(*s);
    return cubeKey(*s);
  };
  EXPECT_NE(k, changed([](scene::Scene& s) { s.meshes[0].vertices[3].position.x += 1e-4f; })) << "geometry";
  EXPECT_NE(k, changed([](scene::Scene& s) { s.meshes[0].vertices[0].uv.y = 0.25f; })) << "uv";
  EXPECT_NE(k, changed([](scene::Scene& s) { std::swap(s.meshes[0].indices[0], s.meshes[0].indices[1]); })) << "indices";
  EXPECT_NE(k, changed([](scene::Scene& s) { s.materials[0].baseColorFactor.g = 0.51f; })) << "base colour";
  EXPECT_NE(k, changed([](scene::Scene& s) { s.materials[0].metallic = 1.0f; })) << "metallic";
  EXPECT_NE(k, changed([](scene::Scene& s) {
    s.materials[0].alphaMode = scene::AlphaMode::Mask;
  })) << "alpha test";
  EXPECT_NE(k, cubeKey(*base, BakeSettings{32})) << "bake settings";
  // Texture contents: one texel differs.
  auto textured = [&](uint8_t texel) {
    auto s = test::makeCubeScene(plainMaterial());
    s->textures.push_back(test::makeCheckerTexture(8, 2, {255, 255, 255}, {0, 0, 0}));
    s->textures[0].rgba8[0] = texel;
    s->textures[0].contentHash = scene::hashBytes(s->textures[0].rgba8.data(), s->textures[0].rgba8.size(), 8);
    s->materials[0].baseColorTexture = scene::TextureRef{0};
    return cubeKey(*s);
  };
  EXPECT_NE(textured(255), textured(254)) << "texture texels";
  EXPECT_NE(k, textured(255)) << "a texture added";
}

// Names, paths and inputs that cannot change the albedo leave the key alone.
TEST(AlbedoKey, IgnoresNamesAndWhatCannotChangeTheAlbedo) {
  auto base = test::makeCubeScene(plainMaterial());
  const AlbedoKey k = cubeKey(*base);
  auto s = test::makeCubeScene(plainMaterial());
  s->name = "renamed";
  s->path = "/elsewhere/renamed.gltf";
  s->meshes[0].name = "another name";
  s->materials[0].name = "another material";
  s->materials[0].roughness = 0.1f;
  s->materials[0].emissiveFactor = glm::vec3(3.0f);
  s->meshes[0].vertices[0].normal = glm::vec3(0.0f, 0.0f, 1.0f);
  s->instances[0].transform = glm::dmat4(2.0);
  EXPECT_EQ(k, cubeKey(*s));
  s->materials[0].baseColorFactor.r = -0.0f + 0.5f;
  EXPECT_EQ(k, cubeKey(*s));
}

TEST(AlbedoKey, StableAcrossFileRenames) {
  const fs::path dir = fs::path(::testing::TempDir()) / "twinlight_renamed_scene";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path content = TWINLIGHT_CONTENT_DIR;
  fs::copy_file(content / "cornell.gltf", dir / "a_different_name.gltf");
  fs::copy_file(content / "cornell.bin", dir / "cornell.bin");
  const scene::Scene original = scene::loadGltf(content / "cornell.gltf");
  const scene::Scene renamed = scene::loadGltf(dir / "a_different_name.gltf");
  SceneKeys a = sceneKeys(original, {}), b = sceneKeys(renamed, {});
  ASSERT_EQ(a.combinations.size(), b.combinations.size());
  for (size_t i = 0; i < a.combinations.size(); ++i) EXPECT_EQ(a.combinations[i].key, b.combinations[i].key);
  EXPECT_EQ(a.instanceCombination, b.instanceCombination);
}

TEST(AlbedoKey, SceneKeysShareIdenticalCombinationsAndSortByKey) {
  const scene::Scene grove = scene::loadGltf(fs::path(TWINLIGHT_CONTENT_DIR) / "grove.gltf");
  SceneKeys keys = sceneKeys(grove, {});
  EXPECT_LE(keys.combinations.size(), grove.meshes.size());
  EXPECT_EQ(keys.instanceCombination.size(), grove.instances.size());
  size_t instances = 0;
  for (size_t i = 0; i < keys.combinations.size(); ++i) {
    instances += keys.combinations[i].instances.size();
    if (i > 0) {
      EXPECT_LT(keys.combinations[i - 1].key, keys.combinations[i].key);
    }
  }
  EXPECT_EQ(instances, grove.instances.size());
}

TEST(AlbedoKey, ShardsPartitionTheKeys) {
  const scene::Scene atrium = scene::loadGltf(fs::path(TWINLIGHT_CONTENT_DIR) / "atrium.gltf");
  SceneKeys keys = sceneKeys(atrium, {});
  for (const Combination& c : keys.combinations) {
    int owners = 0;
    for (uint32_t i = 0; i < 3; ++i) owners += inShard(c.key, i, 3);
    EXPECT_EQ(owners, 1);
  }
}

// A shard's keys spread over every atlas slot, whatever the shard count: its batches fill up
// like a whole bake's (with key % N, 4 shards used half the slots and 42 shards one).
TEST(AlbedoKey, EveryShardUsesEveryAtlasSlot) {
  uint64_t state = 1;
  auto nextKey = [&] {  // splitmix64: keys are uniform 64-bit hashes
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  std::vector<AlbedoKey> keys(200000);
  for (auto& k : keys) k = nextKey();
  const uint32_t slots = AlbedoBaker::maxBatch();
  for (uint32_t count : {2u, 3u, 4u, 6u, 7u, 14u, 16u, 42u}) {
    std::vector<uint32_t> perSlot(slots, 0);
    size_t owned = 0;
    for (AlbedoKey k : keys)
      if (inShard(k, count - 1, count)) ++perSlot[AlbedoBaker::bakeSlot(k)], ++owned;
    const uint32_t fewest = *std::min_element(perSlot.begin(), perSlot.end());
    EXPECT_GT(fewest, 0u) << count << " shards: a slot no key of the shard uses";
    EXPECT_GT(double(fewest), 0.4 * double(owned) / slots) << count << " shards: slots used unevenly";
  }
}

TEST(AlbedoBake, EntryFromViewSumsWeighsByCoverage) {
  // Two views: 100 pixels of 0.2 and 300 pixels of 0.6 (grey): mean 0.5 over 400 pixels.
  std::array<glm::vec4, kViews> sums{};
  sums[0] = glm::vec4(glm::vec3(0.2f * 100), 100.0f);
  sums[3] = glm::vec4(glm::vec3(0.6f * 300), 300.0f);
  auto e = entryFromViewSums(7, sums, 20);
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->rgb.g, 0.5f, 1e-6f);
  EXPECT_NEAR(e->viewCoverage[0], 0.25f, 1e-6f);
  EXPECT_NEAR(e->viewCoverage[3], 0.75f, 1e-6f);
  EXPECT_NEAR(e->coverage, 1.0f / 6.0f, 1e-6f);
  // Variance of the views' means about 0.5, weighted 1:3: (0.09 + 3 * 0.01) / 4.
  EXPECT_NEAR(e->viewVariance, 0.03f, 1e-6f);
  EXPECT_FALSE(entryFromViewSums(7, {}, 20)) << "nothing visible: no entry";
}

TEST(AlbedoBake, ViewProjectionFitsTheBoundsWithReversedDepth) {
  scene::Bounds b;
  b.extend(glm::dvec3(-1.0, 0.0, 2.0));
  b.extend(glm::dvec3(3.0, 1.0, 4.0));
  for (int view = 0; view < kViews; ++view) {
    glm::mat4 m = bakeViewProjection(b, view);
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p(corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y, corner & 4 ? b.max.z : b.min.z);
      glm::vec4 c = m * glm::vec4(glm::vec3(p), 1.0f);
      EXPECT_LE(std::abs(c.x), 1.0f);
      EXPECT_LE(std::abs(c.y), 1.0f);
      EXPECT_GT(c.z, 0.0f);
      EXPECT_LT(c.z, 1.0f);
    }
    // The face nearest the viewer gets the larger depth.
    const int axis = view / 2;
    glm::vec3 nearPoint(b.center()), farPoint(b.center());
    nearPoint[axis] = float(view % 2 == 0 ? b.max[axis] : b.min[axis]);
    farPoint[axis] = float(view % 2 == 0 ? b.min[axis] : b.max[axis]);
    EXPECT_GT((m * glm::vec4(nearPoint, 1.0f)).z, (m * glm::vec4(farPoint, 1.0f)).z) << "view " << view;
  }
}

BakedEntry row(AlbedoKey key, glm::vec3 rgb, const std::string& label = "mesh / material") {
  BakedEntry e;
  e.key = key;
  e.rgb = rgb;
  e.coverage = 0.5f;
  e.viewCoverage = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
  e.viewVariance = 0.25f;
  e.bakedAt = "2026-01-01T00:00:00Z";
  e.label = label;
  return e;
}

TEST(AlbedoDatabase, CreatesWritesAndReadsBack) {
  const fs::path file = tempFile("basic.db");
  {
    AlbedoDatabase db(file);
    EXPECT_EQ(db.schemaVersion(), AlbedoDatabase::kSchemaVersion);
    EXPECT_EQ(db.revision(), 0u);
    db.writeBaked({row(1, glm::vec3(0.1f, 0.2f, 0.3f)), row(2, glm::vec3(0.9f))});
    db.writeOverrides({{1, glm::vec3(1.0f, 0.0f, 0.0f), "2026-01-02T00:00:00Z", "red"}}, {});
  }
  AlbedoDatabase db(file, false);
  auto baked = db.baked();
  ASSERT_EQ(baked.size(), 2u);
  EXPECT_EQ(baked[1].rgb, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(baked[1].viewCoverage[5], 0.6f);
  EXPECT_EQ(baked[1].viewVariance, 0.25f);
  EXPECT_EQ(baked[1].bakerVersion, kBakerVersion);
  EXPECT_EQ(baked[1].label, "mesh / material");
  EXPECT_TRUE(db.hasBaked(2));
  EXPECT_FALSE(db.hasBaked(3));
  EXPECT_EQ(db.overrides().at(1).rgb, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(db.baked().size(), 2u) << "overrides live in their own table";
  EXPECT_EQ(db.revision(), 2u);
  db.writeOverrides({}, {1});
  EXPECT_TRUE(db.overrides().empty());
}

TEST(AlbedoDatabase, MissingFileWithoutCreateIsAnError) {
  const fs::path file = tempFile("absent.db");
  EXPECT_THROW(AlbedoDatabase(file, false), DatabaseError);
  EXPECT_FALSE(fs::exists(file));
}

// The caller's failure halfway through a write leaves nothing of it.
TEST(AlbedoDatabase, AFailedTransactionLeavesTheLastCommittedState) {
  const fs::path file = tempFile("rollback.db");
  AlbedoDatabase db(file);
  db.writeBaked({row(1, glm::vec3(0.5f))});
  EXPECT_THROW(db.writeBaked({row(2, glm::vec3(0.5f)), row(3, glm::vec3(0.5f))}, [] { throw std::runtime_error("killed"); }),
               std::runtime_error);
  EXPECT_EQ(db.baked().size(), 1u);
  EXPECT_EQ(db.revision(), 1u);
}

void expectRefusedUntouched(const fs::path& file, const std::string& expected) {
  const std::string before = fileBytes(file);
  try {
    AlbedoDatabase db(file);
    FAIL() << "opened " << file;
  } catch (const DatabaseError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << "names the file: " << e.what();
  }
  EXPECT_EQ(fileBytes(file), before) << "the file was modified";
}

TEST(AlbedoDatabase, RefusesAForeignFileAndLeavesItUntouched) {
  const fs::path file = tempFile("foreign.txt");
  std::ofstream(file) << "this is a text file, not a database\n";
  expectRefusedUntouched(file, "not an SQLite file");
}

TEST(AlbedoDatabase, RefusesAnotherApplicationsSqliteDatabase) {
  const fs::path file = tempFile("other_app.db");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE songs(title TEXT); INSERT INTO songs VALUES('x');", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  expectRefusedUntouched(file, "another application");
}

TEST(AlbedoDatabase, RefusesADamagedFile) {
  const fs::path file = tempFile("damaged.db");
  {
    AlbedoDatabase db(file);
    std::vector<BakedEntry> many;
    for (AlbedoKey k = 0; k < 400; ++k) many.push_back(row(k, glm::vec3(0.5f), std::string(200, 'x')));
    db.writeBaked(many);
  }
  // Overwrite the middle of the file (past the header page) with garbage.
  std::string bytes = fileBytes(file);
  ASSERT_GT(bytes.size(), 16384u);
  for (size_t i = 8192; i < 12288; ++i) bytes[i] = char(i * 7);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  expectRefusedUntouched(file, "damaged");
}

TEST(AlbedoDatabase, RefusesANewerSchema) {
  const fs::path file = tempFile("newer.db");
  { AlbedoDatabase db(file); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "PRAGMA user_version = 99", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  expectRefusedUntouched(file, "newer Twinlight");
}

// A negative user_version (SQLite stores any 32-bit integer) is no schema: refused before any
// migration runs (fuzz_albedo_db found it indexing the migrations at -1).
TEST(AlbedoDatabase, RefusesANegativeSchema) {
  const fs::path file = tempFile("negative.db");
  { AlbedoDatabase db(file); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "PRAGMA user_version = -1", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  expectRefusedUntouched(file, "schema -1, which no Twinlight writes");
}

// A schema-1 file (before labels) opens, migrates and keeps its rows.
TEST(AlbedoDatabase, MigratesAVersionOneFile) {
  const fs::path file = tempFile("v1.db");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  const std::string v1 = fmt::format(
      "PRAGMA application_id = {};"
      "CREATE TABLE meta(name TEXT PRIMARY KEY, value TEXT NOT NULL);"
      "CREATE TABLE baked(key TEXT PRIMARY KEY, r REAL NOT NULL, g REAL NOT NULL, b REAL NOT NULL,"
      " coverage REAL NOT NULL, view_coverage TEXT NOT NULL, view_variance REAL NOT NULL,"
      " baker_version INTEGER NOT NULL, baked_at TEXT NOT NULL);"
      "CREATE TABLE overrides(key TEXT PRIMARY KEY, r REAL NOT NULL, g REAL NOT NULL, b REAL NOT NULL, edited_at TEXT NOT NULL);"
      "INSERT INTO baked VALUES('00000000000000aa', 0.25, 0.5, 0.75, 1, '1,1,1,1,1,1', 0, 1, '2025-01-01T00:00:00Z');"
      "INSERT INTO overrides VALUES('00000000000000aa', 1, 0, 0, '2025-01-02T00:00:00Z');"
      "PRAGMA user_version = 1;",
      AlbedoDatabase::kApplicationId);
  ASSERT_EQ(sqlite3_exec(db, v1.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  AlbedoDatabase migrated(file);
  EXPECT_EQ(migrated.schemaVersion(), AlbedoDatabase::kSchemaVersion);
  auto baked = migrated.findBaked(0xaa);
  ASSERT_TRUE(baked);
  EXPECT_EQ(baked->rgb, glm::vec3(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(baked->label, "");
  EXPECT_EQ(migrated.overrides().at(0xaa).rgb, glm::vec3(1.0f, 0.0f, 0.0f));
  migrated.writeBaked({row(0xbb, glm::vec3(0.1f))});
  EXPECT_EQ(migrated.revision(), 1u);
}

TEST(AlbedoDatabase, MergeReportsConflictsAndNeverLosesOverrides) {
  const fs::path a = tempFile("merge_a.db"), b = tempFile("merge_b.db");
  AlbedoDatabase da(a), db(b);
  da.writeBaked({row(1, glm::vec3(0.1f)), row(2, glm::vec3(0.2f))});
  db.writeBaked({row(2, glm::vec3(0.2f)), row(3, glm::vec3(0.3f)), row(1, glm::vec3(0.15f))});
  da.writeOverrides({{1, glm::vec3(1, 0, 0), "2026-01-01T00:00:00Z", "x"}, {5, glm::vec3(0, 0, 1), "2026-01-01T00:00:00Z", "y"}}, {});
  db.writeOverrides({{1, glm::vec3(0, 1, 0), "2026-02-01T00:00:00Z", "x"}, {6, glm::vec3(1), "2026-01-01T00:00:00Z", "z"}}, {});
  MergeReport r = da.mergeFrom(db);
  EXPECT_EQ(r.bakedAdded, 1u);
  EXPECT_EQ(r.bakedSame, 1u);
  EXPECT_EQ(r.overridesAdded, 1u);
  ASSERT_EQ(r.conflicts.size(), 2u);
  auto baked = da.baked();
  EXPECT_EQ(baked.size(), 3u);
  EXPECT_EQ(baked[1].rgb, glm::vec3(0.1f)) << "a baked conflict keeps this database's row";
  auto overrides = da.overrides();
  EXPECT_EQ(overrides.size(), 3u);
  EXPECT_EQ(overrides[1].rgb, glm::vec3(0, 1, 0)) << "the later edit wins";
  EXPECT_EQ(overrides[5].rgb, glm::vec3(0, 0, 1));
  EXPECT_EQ(overrides[6].rgb, glm::vec3(1));
}

TEST(AlbedoLibrary, ResolvesOverrideThenBakedThenTextureAverage) {
  auto s = test::makeCubeScene(plainMaterial(glm::vec3(0.5f)));
  AlbedoLibrary lib(*s);
  ASSERT_EQ(lib.entries().size(), 1u);
  const glm::vec3 average = scene::materialAverageAlbedo(*s, s->materials[0]);
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::TextureAverage);
  EXPECT_EQ(glm::vec3(lib.instanceAlbedo()[0]), average);

  const fs::path file = tempFile("library.db");
  auto db = std::make_unique<AlbedoDatabase>(file);
  db->writeBaked({row(lib.entries()[0].combination.key, glm::vec3(0.3f), lib.entries()[0].combination.label)});
  lib.attach(std::move(db));
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::Baked);
  EXPECT_EQ(glm::vec3(lib.instanceAlbedo()[0]), glm::vec3(0.3f));
  EXPECT_EQ(lib.entryOf(0).textureAverage, average) << "the fallback is always known";

  const uint64_t v = lib.version();
  lib.setOverride(0, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_GT(lib.version(), v);
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::Override);
  EXPECT_EQ(glm::vec3(lib.instanceAlbedo()[0]), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_TRUE(lib.unsaved());
}

TEST(AlbedoLibrary, UndoRedoEveryEditAndMergeADrag) {
  auto s = test::makeCubeScene(plainMaterial());
  AlbedoLibrary lib(*s);
  lib.setOverride(0, glm::vec3(0.1f));
  lib.setOverride(0, glm::vec3(0.2f), true);  // the same drag
  lib.setOverride(0, glm::vec3(0.3f), true);
  lib.setOverride(0, glm::vec3(0.9f));        // a new edit
  lib.clearOverride(0);
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::TextureAverage);
  ASSERT_TRUE(lib.undo());
  EXPECT_EQ(*lib.entryOf(0).override, glm::vec3(0.9f));
  ASSERT_TRUE(lib.undo());
  EXPECT_EQ(*lib.entryOf(0).override, glm::vec3(0.3f)) << "a drag is one step";
  ASSERT_TRUE(lib.undo());
  EXPECT_FALSE(lib.entryOf(0).override);
  EXPECT_FALSE(lib.undo());
  ASSERT_TRUE(lib.redo());
  EXPECT_EQ(*lib.entryOf(0).override, glm::vec3(0.3f));
  lib.setOverride(0, glm::vec3(0.5f));
  EXPECT_FALSE(lib.canRedo()) << "a new edit drops the redo history";
}

TEST(AlbedoLibrary, SaveWritesOverridesAndAReopenSeesThem) {
  auto s = test::makeCubeScene(plainMaterial());
  const fs::path file = tempFile("save.db");
  {
    AlbedoLibrary lib(*s);
    EXPECT_THROW(lib.save(), DatabaseError) << "no database to save to";
    lib.attach(std::make_unique<AlbedoDatabase>(file));
    lib.setOverride(0, glm::vec3(0.25f, 0.5f, 0.75f));
    lib.save();
    EXPECT_FALSE(lib.unsaved());
  }
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(file));
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::Override);
  EXPECT_EQ(glm::vec3(lib.instanceAlbedo()[0]), glm::vec3(0.25f, 0.5f, 0.75f));
  lib.clearOverride(0);
  lib.save();
  EXPECT_TRUE(lib.database()->overrides().empty());
}

TEST(AlbedoLibrary, MarksStaleWhenTheContentChangedSinceTheBake) {
  auto s = test::makeCubeScene(plainMaterial());
  const fs::path file = tempFile("stale.db");
  AlbedoLibrary original(*s);
  {
    AlbedoDatabase db(file);
    db.writeBaked({row(original.entries()[0].combination.key, glm::vec3(0.5f), original.entries()[0].combination.label)});
  }
  s->materials[0].baseColorFactor = glm::vec4(0.8f, 0.1f, 0.1f, 1.0f);  // edited after the bake
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(file));
  EXPECT_FALSE(lib.entryOf(0).baked);
  EXPECT_TRUE(lib.entryOf(0).stale);
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::TextureAverage);
}

// An override saved before the material changed is listed with its colour and the reason,
// survives saves, and re-applying it moves it to the new key in one undoable step.
TEST(AlbedoLibrary, AnOverrideOrphanedByAContentChangeIsListedAndReapplied) {
  auto s = test::makeCubeScene(plainMaterial());
  const fs::path file = tempFile("orphan.db");
  const glm::vec3 colour(0.2f, 0.4f, 0.6f);
  AlbedoKey oldKey = 0;
  {
    AlbedoLibrary lib(*s);
    lib.attach(std::make_unique<AlbedoDatabase>(file));
    EXPECT_EQ(lib.orphanCount(), 0u);
    lib.setOverride(0, colour);
    lib.save();
    oldKey = lib.entries()[0].combination.key;
  }
  s->materials[0].baseColorFactor = glm::vec4(0.8f, 0.1f, 0.1f, 1.0f);  // re-exported with another colour
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(file));
  EXPECT_FALSE(lib.entryOf(0).override) << "the new key has no override";
  ASSERT_EQ(lib.orphanCount(), 1u);
  const OrphanOverride& o = lib.orphans()[0];
  EXPECT_EQ(o.key, oldKey);
  EXPECT_EQ(o.rgb, colour);
  EXPECT_EQ(o.label, lib.entries()[0].combination.label);
  ASSERT_EQ(o.sameLabel, std::optional<uint32_t>(0u));
  EXPECT_TRUE(o.inDatabase);
  EXPECT_FALSE(o.editedAt.empty());
  EXPECT_NE(orphanReason(o).find("changed"), std::string::npos);
  EXPECT_FALSE(lib.unsaved());

  lib.save();  // saving without acting keeps it
  EXPECT_EQ(lib.database()->overrides().count(oldKey), 1u);

  lib.reapplyOrphan(0, *o.sameLabel);
  EXPECT_EQ(lib.orphanCount(), 0u);
  EXPECT_EQ(lib.entryOf(0).source, AlbedoSource::Override);
  EXPECT_EQ(*lib.entryOf(0).override, colour);
  EXPECT_TRUE(lib.unsaved());
  ASSERT_TRUE(lib.undo()) << "one step";
  EXPECT_EQ(lib.orphanCount(), 1u);
  EXPECT_FALSE(lib.entryOf(0).override);
  ASSERT_TRUE(lib.redo());
  lib.save();
  const auto rows = lib.database()->overrides();
  EXPECT_EQ(rows.count(oldKey), 0u) << "the old key's row is gone";
  ASSERT_EQ(rows.count(lib.entries()[0].combination.key), 1u);
  EXPECT_EQ(rows.at(lib.entries()[0].combination.key).rgb, colour);
}

// An override of a combination the scene no longer has (another scene's, or removed) is
// listed without a same-label match and is removed from the database only when deleted.
TEST(AlbedoLibrary, AnOrphanIsDeletedOnlyWhenAskedAndTheDeleteUndoes) {
  auto s = test::makeCubeScene(plainMaterial());
  const fs::path file = tempFile("orphan_delete.db");
  {
    AlbedoDatabase db(file);
    db.writeOverrides({{0x1234, glm::vec3(0.9f, 0.8f, 0.7f), "2026-12-01T00:00:00Z", "gone / paint"}}, {});
  }
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(file));
  ASSERT_EQ(lib.orphanCount(), 1u);
  EXPECT_FALSE(lib.orphans()[0].sameLabel);
  EXPECT_NE(orphanReason(lib.orphans()[0]).find("no mesh + material"), std::string::npos);
  lib.deleteOrphan(0);
  EXPECT_EQ(lib.orphanCount(), 0u);
  EXPECT_TRUE(lib.unsaved());
  ASSERT_TRUE(lib.undo());
  EXPECT_EQ(lib.orphanCount(), 1u);
  EXPECT_FALSE(lib.unsaved());
  ASSERT_TRUE(lib.redo());
  EXPECT_EQ(lib.database()->overrides().size(), 1u) << "nothing leaves the database before a save";
  lib.save();
  EXPECT_TRUE(lib.database()->overrides().empty());
  EXPECT_FALSE(lib.unsaved());
}

// An unsaved override whose key vanished in a reload is kept as an orphan, counts as
// unsaved, and a save writes it under its old key (it outlives the session).
// A bake ends by reloading the database (its new rows). An override undone after a save is
// unsaved work too: the value before the saved edit, which the database no longer holds. The
// reload used to keep only entries with an applied edit, so the saved colour came back and the
// undo was lost (the editor soak, seed 2: undo, then Re-bake all).
TEST(AlbedoLibrary, AReloadAfterAnUndoKeepsTheUndoneValue) {
  auto s = test::makeCubeScene(plainMaterial());
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(tempFile("undo_reload.db")));
  lib.setOverride(0, glm::vec3(0.2f, 0.4f, 0.6f));
  lib.save();
  lib.setOverride(0, glm::vec3(0.9f, 0.1f, 0.1f));
  lib.save();
  ASSERT_TRUE(lib.undo());
  EXPECT_TRUE(lib.unsaved());
  lib.reload();
  ASSERT_TRUE(lib.entryOf(0).override);
  EXPECT_EQ(*lib.entryOf(0).override, glm::vec3(0.2f, 0.4f, 0.6f)) << "the undo is kept, not the database's colour";
  EXPECT_TRUE(lib.unsaved());
  ASSERT_TRUE(lib.redo());
  lib.reload();
  EXPECT_EQ(*lib.entryOf(0).override, glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_FALSE(lib.unsaved());
  // Undone to before the first edit: no override, while the database holds one.
  ASSERT_TRUE(lib.undo());
  ASSERT_TRUE(lib.undo());
  lib.reload();
  EXPECT_FALSE(lib.entryOf(0).override) << "the override undone away stays away";
  lib.save();
  EXPECT_TRUE(lib.database()->overrides().empty());
}

TEST(AlbedoLibrary, AnUnsavedOverrideCarriedOverAReloadIsKeptAndSaved) {
  auto s = test::makeCubeScene(plainMaterial());
  const fs::path file = tempFile("orphan_kept.db");
  AlbedoLibrary before(*s);
  const AlbedoKey oldKey = before.entries()[0].combination.key;
  const std::string label = before.entries()[0].combination.label;
  s->materials[0].metallic = 1.0f;
  AlbedoLibrary lib(*s);
  lib.attach(std::make_unique<AlbedoDatabase>(file));
  lib.keepOrphan(lib.entries()[0].combination.key, glm::vec3(0.5f), label);
  EXPECT_EQ(lib.orphanCount(), 0u) << "a key the scene still has is no orphan";
  lib.keepOrphan(oldKey, glm::vec3(0.1f, 0.2f, 0.3f), label);
  ASSERT_EQ(lib.orphanCount(), 1u);
  EXPECT_EQ(lib.orphans()[0].sameLabel, std::optional<uint32_t>(0u));
  EXPECT_FALSE(lib.orphans()[0].inDatabase);
  EXPECT_TRUE(lib.unsaved()) << "the orphan is only in memory";
  lib.save();
  EXPECT_FALSE(lib.unsaved());
  ASSERT_EQ(lib.database()->overrides().count(oldKey), 1u);
  EXPECT_EQ(lib.database()->overrides().at(oldKey).label, label);
}

}  // namespace
}  // namespace tl::albedo
