// A compare sweep: every configuration (paths and --settings variants) measured from every
// view of a grid of scenes x cameras, each view against its own reference. A view is the
// unit a shard takes: its reference renders once, in the process that measures every
// configuration against it, so no two shards ever render the same reference. Views go to
// shards in contiguous blocks of the grid's order (a shard loads few scenes).
//
// Unsharded, each view's report goes to its folder and, with more than one view, the sweep's
// own report.json / report.html (one row per configuration with its mean figures over the
// views, the Pareto plot of those, and a link per view) to the top. A shard writes its views'
// folders and shard.json; merging the shards' folders copies the views' reports and writes
// the same top-level report from them, so its figures are those of an unsharded run.
#pragma once

#include "session/compare.h"
#include "session/shard.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

struct SweepView {
  std::string sceneFile;  // as given on the command line
  std::string camera;     // "" = the command line's camera; else a name the view setter knows
  std::string dir;        // report folder relative to the output ("" for a one-view sweep)
};

struct SweepPlan {
  std::vector<SweepView> views;  // grid order: scene-major
  // What decides the figures besides the views and CompareOptions (size, light, view and
  // render options as given): shards of one sweep must agree on it.
  nlohmann::json settings = nlohmann::json::object();
};

// Report folders for each (scene, camera) pair: "", "<camera>", "<scene>" or
// "<scene>/<camera>" as the grid needs. Throws SessionError when two scenes share a file stem.
SweepPlan planSweep(const std::vector<std::string>& sceneFiles,
                    const std::function<std::vector<std::string>(const std::string& sceneFile)>& cameraNames);

// Everything the figures depend on, as report.json's "grid" and shard.json's check.
nlohmann::json sweepGrid(const SweepPlan& plan, const CompareOptions& options);

struct SweepCallbacks {
  // Loads the scene and applies the command line's settings (size, light, view, options).
  std::function<void(Session&, const std::string& sceneFile)> loadScene;
  // Points the loaded scene's session at the view (camera "" = the command line's).
  std::function<void(Session&, const SweepView&)> setView;
  // Called after each view's report is written (printing its figures).
  std::function<void(const SweepView&, const nlohmann::json& report)> viewDone;
  Progress progress;
};

struct SweepOutcome {
  size_t views = 0;          // views measured by this process
  size_t gateFailures = 0;   // figures over their thresholds, in those views
  size_t gateWithinNoise = 0;  // figures whose interval holds their threshold (the gate cannot tell)
  std::optional<nlohmann::json> sweepReport;  // the top-level report when one was written
};

// Runs the views of `shard` (every view when empty) into options.outDir.
SweepOutcome runSweep(Session& session, const SweepPlan& plan, const CompareOptions& options,
                      const std::optional<Shard>& shard, const SweepCallbacks& callbacks);

// `compare --merge DIR... --out OUT`: checks that the folders are the finished shards 0..N-1 of
// one sweep (same grid, each index once), copies every view's report into OUT and writes the
// sweep's report there. No GPU. Throws SessionError naming the folder and what is wrong.
// Returns the top-level report (the one view's report.json for a one-view sweep).
nlohmann::json mergeSweep(const std::vector<std::filesystem::path>& shardDirs, const std::filesystem::path& out);

// Figures over their thresholds in a report (a view's, or a sweep's).
size_t gateFailureCount(const nlohmann::json& report);
// The figures of a report's gate within the reference's noise of their thresholds: neither
// passed nor failed (compare.cpp, evaluateGate).
size_t gateWithinNoiseCount(const nlohmann::json& report);

}  // namespace tl::session
