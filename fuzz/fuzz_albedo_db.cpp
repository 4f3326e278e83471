// libFuzzer target: opening an albedo database (albedo/albedo_database.h) as `bake --list`,
// `--db` and `--albedo-db` do, then reading every entry. The bytes are written to a file of a
// private folder first (SQLite opens files by name). A DatabaseError is a refusal ("not an
// albedo database", "damaged"); anything else is a finding.
#include "albedo/albedo_database.h"
#include "fuzz_folder.h"

#include <fstream>

static std::filesystem::path gFolder;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  gFolder = tl::fuzz::privateFolder("albedo");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = gFolder / "fuzz.db";
  std::error_code ec;
  for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::filesystem::remove(file.string() + suffix, ec);
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    tl::albedo::AlbedoDatabase db(file, false);
    size_t entries = db.baked().size() + db.overrides().size();
    (void)entries;
  } catch (const tl::albedo::DatabaseError&) {
  }
  return 0;
}
