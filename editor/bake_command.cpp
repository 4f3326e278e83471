#include "bake_command.h"

#include "cli_args.h"

#include "session/session.h"

#include <fmt/format.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>

namespace {

using tl::session::SessionError;
namespace albedo = tl::albedo;

std::pair<uint32_t, uint32_t> parseShard(const std::string& text) {
  unsigned i = 0, n = 0;
  char slash = 0;
  if (std::sscanf(text.c_str(), "%u%c%u", &i, &slash, &n) != 3 || slash != '/' || n == 0 || i >= n)
    throw SessionError(fmt::format("--shard `{}` is not i/N with 0 <= i < N", text));
  return {i, n};
}

int listDatabase(const std::string& file) {
  albedo::AlbedoDatabase db(file, false);
  fmt::print("{}: schema {}, revision {}\n", file, db.schemaVersion(), db.revision());
  for (auto& [key, e] : db.baked())
    fmt::print("baked    {} {:.6f} {:.6f} {:.6f} coverage {:.4f} view-variance {:.6f} v{} {}\n", albedo::keyToHex(key),
               e.rgb.r, e.rgb.g, e.rgb.b, e.coverage, e.viewVariance, e.bakerVersion, e.label);
  for (auto& [key, e] : db.overrides())
    fmt::print("override {} {:.6f} {:.6f} {:.6f} edited {} {}\n", albedo::keyToHex(key), e.rgb.r, e.rgb.g, e.rgb.b, e.editedAt,
               e.label);
  return 0;
}

int mergeDatabases(const BakeArgs& a) {
  // Every input is opened (and so checked) before the output is touched.
  std::vector<std::unique_ptr<albedo::AlbedoDatabase>> inputs;
  for (const std::string& f : a.merge) inputs.push_back(std::make_unique<albedo::AlbedoDatabase>(f, false));
  albedo::AlbedoDatabase out(a.db);
  size_t conflicts = 0;
  for (auto& in : inputs) {
    albedo::MergeReport r = out.mergeFrom(*in);
    fmt::print("{}: {} baked added, {} already there; {} overrides added, {} already there; {} conflicts\n",
               in->file().string(), r.bakedAdded, r.bakedSame, r.overridesAdded, r.overridesSame, r.conflicts.size());
    for (const std::string& c : r.conflicts) fmt::print("  conflict: {}\n", c);
    conflicts += r.conflicts.size();
  }
  fmt::print("merged {} database(s) into {}: {} baked, {} overrides, {} conflicts\n", inputs.size(), a.db, out.baked().size(),
             out.overrides().size(), conflicts);
  return 0;
}

}  // namespace

int runBake(const BakeArgs& a, const std::string& defaultScene) {
  if (a.db.empty()) throw SessionError("bake needs --db FILE");
  if (a.list) return listDatabase(a.db);
  if (!a.merge.empty()) return mergeDatabases(a);

  albedo::BakeOptions options;
  options.settings.tileSize = a.tileSize;
  if (a.tileSize < 8 || a.tileSize > 256) throw SessionError("--tile must be between 8 and 256 pixels");
  if (!a.shard.empty()) std::tie(options.shardIndex, options.shardCount) = parseShard(a.shard);
  options.batchSize = a.batch;
  options.force = a.force;
  // Crash tests: die by SIGKILL inside batch N's transaction, after its rows are written.
  if (const char* kill = std::getenv("TWINLIGHT_TEST_KILL_IN_BATCH"); kill && *kill) {
    const uint32_t at = uint32_t(std::strtoul(kill, nullptr, 10));
    options.beforeCommit = [at](uint32_t batch) {
      if (batch == at) std::raise(SIGKILL);
    };
  }

  tl::session::Session session;
  session.loadScene(a.scene.empty() ? defaultScene : a.scene, tl::scene::LoadOptions{a.allowOutsideFiles});
  session.openAlbedoDatabase(a.db);
  const auto start = std::chrono::steady_clock::now();
  auto job = session.startAlbedoBake(options);
  auto bar = [&] {
    const auto& p = job->progress();
    const double f = p.total ? double(p.done) / p.total : 1.0;
    const int filled = int(f * 30.0 + 0.5);
    fmt::print(stderr, "\r[{:30}] {:4}/{:<4} baked {} skipped {} failed {}", std::string(size_t(filled), '#'), p.done, p.total,
               p.baked, p.skipped, p.failed);
  };
  bar();
  while (job->step()) bar();
  bar();
  fmt::print(stderr, "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& p = job->progress();
  for (const std::string& f : p.failures) fmt::print("failed: {}\n", f);
  fmt::print("{}: {} keys{}: baked {}, skipped {} (up to date), failed {} in {:.2f} s ({:.1f} keys/s baking)\n",
             session.scene().name, p.total, a.shard.empty() ? "" : fmt::format(" in shard {}", a.shard), p.baked, p.skipped,
             p.failed, seconds, p.gpuSeconds > 0.0 ? p.baked / p.gpuSeconds : 0.0);
  fmt::print("database {}: {} baked, {} overrides, {} bytes\n", a.db, session.albedo().database()->baked().size(),
             session.albedo().database()->overrides().size(), std::filesystem::file_size(a.db));
  if (p.failed) {
    fmt::print(stderr, "twinlight: error: {} of {} keys failed to bake (listed above)\n", p.failed, p.total);
    return 1;
  }
  return exitStatus(session);
}
