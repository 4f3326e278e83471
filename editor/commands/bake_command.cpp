// `twinlight bake`: the albedo database from the command line — bake scenes (or a shard of
// their keys: by hand, or from a Slurm array / Kubernetes Indexed Job), merge databases, list
// what one holds.
#include "cli_command.h"
#include "render_options.h"

#include "cli_args.h"
#include "cli_output.h"

#include "session/session.h"
#include "session/shard.h"

#include <fmt/format.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>

namespace tl::editor {
namespace {

using session::SessionError;

struct BakeArgs {
  std::vector<std::string> scenes;  // baked in order; a key two scenes share is baked once
  std::string db;
  std::string shard;                      // "i/N" or "auto"
  std::optional<std::string> shardCount;  // with auto, where the scheduler gives no count
  uint32_t batch = 0;                     // combinations per submission, 0 = as many as fit
  uint32_t tileSize = 64;
  bool force = false;
  bool list = false;
  std::vector<std::string> merge;  // databases to merge into --db
  bool allowOutsideFiles = false;  // the scene may read files outside its folder
};

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

int runBake(const BakeArgs& a) {
  if (a.db.empty()) throw SessionError("bake needs --db FILE");
  if (a.list) return listDatabase(a.db);
  if (!a.merge.empty()) return mergeDatabases(a);

  albedo::BakeOptions options;
  options.settings.tileSize = a.tileSize;
  if (a.tileSize < 8 || a.tileSize > 256) throw SessionError("--tile must be between 8 and 256 pixels");
  std::optional<session::Shard> shard;
  if (!a.shard.empty() || a.shardCount) {
    if (a.shard.empty()) throw session::ShardError("--shard-count goes with --shard auto");
    shard = session::resolveShard(a.shard, a.shardCount);
    options.shardIndex = shard->index;
    options.shardCount = shard->count;
    fmt::print("shard {}/{}: {}\n", shard->index, shard->count, shard->source);
  }
  options.batchSize = a.batch;
  options.force = a.force;
  // Crash tests: die by SIGKILL inside batch N's transaction, after its rows are written.
  if (const char* kill = std::getenv("TWINLIGHT_TEST_KILL_IN_BATCH"); kill && *kill) {
    const uint32_t at = uint32_t(std::strtoul(kill, nullptr, 10));
    options.beforeCommit = [at](uint32_t batch) {
      if (batch == at) std::raise(SIGKILL);
    };
  }

  const std::vector<std::string> scenes = a.scenes.empty() ? std::vector<std::string>{defaultScene().string()} : a.scenes;
  session::Session session;
  uint32_t failed = 0;
  for (const std::string& file : scenes) {
    // Keys an earlier scene baked are in the database by now: this scene skips them.
    const auto loadStart = std::chrono::steady_clock::now();
    session.loadScene(file, scene::LoadOptions{a.allowOutsideFiles});
    session.openAlbedoDatabase(a.db);
    const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
    const auto start = std::chrono::steady_clock::now();
    auto job = session.startAlbedoBake(options);
    {
      Progress progress("bake " + session.scene().name);
      auto report = [&] {
        const auto& p = job->progress();
        progress.update(p.total ? double(p.done) / p.total : 1.0,
                        fmt::format("{}/{} keys: baked {}, skipped {}, failed {}", p.done, p.total, p.baked, p.skipped, p.failed));
      };
      report();
      while (job->step()) report();
      report();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& p = job->progress();
    for (const std::string& f : p.failures) fmt::print("failed: {}\n", f);
    // A mesh nothing of which is visible (fully cut out, empty) has no albedo a ray could read:
    // noted, not stored, not a failure.
    for (const std::string& k : p.invisibleKeys) fmt::print("not visible from any direction, nothing to bake: {}\n", k);
    fmt::print("{}: {} keys{}: baked {}, skipped {} (up to date), failed {}{} in {:.2f} s ({:.1f} keys/s baking); "
               "scene loaded in {:.2f} s\n",
               session.scene().name, p.total, shard ? fmt::format(" in shard {}/{}", shard->index, shard->count) : "",
               p.baked, p.skipped, p.failed,
               p.invisible ? fmt::format(", {} not visible (fully cut out or empty: no ray hits them)", p.invisible) : "",
               seconds, p.gpuSeconds > 0.0 ? p.baked / p.gpuSeconds : 0.0, loadSeconds);
    failed += p.failed;
  }
  fmt::print("database {}: {} baked, {} overrides, {} bytes\n", a.db, session.albedo().database()->baked().size(),
             session.albedo().database()->overrides().size(), std::filesystem::file_size(a.db));
  if (failed) {
    fmt::print(stderr, "twinlight: error: {} key(s) failed to bake (listed above)\n", failed);
    return 1;
  }
  return exitStatus(session);
}

class BakeCommand : public CliCommand {
 public:
  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("bake", "bake the per-instance albedo database (or merge or list databases)");
    cmd->add_option("--scene", a_.scenes,
                    "glTF file(s), baked in order into one database (a key they share is baked once); default "
                    "content/atrium.gltf");
    cmd->add_option("--db", a_.db, "the albedo database (SQLite), created when missing")->required();
    cmd->add_option("--shard", a_.shard,
                    "bake only shard i of N (i/N, 0-based): a fixed subset of the keys; or `auto` from a Slurm array "
                    "(SLURM_ARRAY_TASK_ID) or Kubernetes Indexed Job (JOB_COMPLETION_INDEX)");
    cmd->add_option("--shard-count", a_.shardCount,
                    "with --shard auto under a Kubernetes Indexed Job: the shard count (else TWINLIGHT_SHARD_COUNT)");
    cmd->add_option("--batch", a_.batch, "combinations per GPU submission (default: as many as fit, 42)");
    cmd->add_option("--tile", a_.tileSize, "pixels per side of each of the 6 views (part of every key)")->capture_default_str();
    cmd->add_flag("--force", a_.force, "re-bake keys the database already holds");
    cmd->add_flag("--list", a_.list, "print the database's baked entries and overrides, bake nothing");
    cmd->add_option("--merge", a_.merge, "merge these databases into --db (conflicts reported, overrides kept)");
    cmd->add_flag("--allow-outside-files", a_.allowOutsideFiles,
                  "let the scene read buffers and images outside its own folder (../, absolute paths, links out)");
    return cmd;
  }
  int run() override { return runBake(a_); }

 private:
  BakeArgs a_;
};

}  // namespace

std::unique_ptr<CliCommand> makeBakeCommand() { return std::make_unique<BakeCommand>(); }

}  // namespace tl::editor
