// `twinlight tune`: the cheapest settings of a lighting path that a scene (or a library of
// scenes) needs, found against the reference.
//
// The search is successive halving over a seeded population of configurations
// (session/tune_space.h): every configuration runs at a quarter of the image's side and a
// quarter of the frames (three rungs), the best third by Pareto rank (session/tune_front.h) goes
// on to the next rung at twice the side and twice the frames, and so on to the full size, where
// the front is measured. A configuration's error is the mean over the last quarter of its frames,
// its interval widened by their spread. The path's defaults ride along to every rung, so the report always holds them at
// full fidelity. Each measurement is a `compare` run of a chunk of configurations beside the
// baseline path's defaults: frame times are taken as ratios to the baseline in the same run, so
// the machine's load between runs cancels out.
//
// Then, per budget, the cheapest configuration whose error is within the reference's noise of
// the best one under the budget is tried without each feature it has on (kSettingFeature): the
// features whose removal does not make the error significantly worse are left off ("not needed
// here"), checked together once more.
//
// Everything lives in the output folder: a measurement is a compare report in its own folder,
// written last, so a killed run resumes where it stopped, and shards of a job array (sharing
// the folder) each take a block of a stage's measurements; a stage starts only once the
// previous one is complete (a shard that finds it incomplete says so and stops).
#pragma once

#include "session/compare.h"
#include "session/shard.h"
#include "session/sweep.h"
#include "session/tune_front.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

// "1.3x-legacy" (the baseline's frame time times 1.3, measured in the same run) or "25ms" (GPU
// frame time). SessionError naming what is wrong otherwise.
struct TuneBudget {
  std::string text;
  double ratio = 0.0;  // over the baseline's frame time, when given so
  double ms = 0.0;     // when given in milliseconds
};
TuneBudget parseTuneBudget(const std::string& text, const std::string& baseline);

struct TuneOptions {
  std::string path = "rt";          // the lighting path whose settings are searched
  std::string baseline = "legacy";  // measured beside every chunk: the unit of time
  std::vector<TuneBudget> budgets;
  // The error minimised, one of significanceMetrics(). FLIP by default: relMSE is ruled by a few
  // fireflies (rt's defaults on cornell at 160x90: relMSE_norm 3.4 on one view, 0.084 at 320x180,
  // FLIP_norm 0.080 and 0.065), so a halving on it ranks by chance at the low rungs.
  std::string metric = "FLIP_norm";
  // A second figure that must not get significantly worse (tune_front.h); "" for none.
  std::string guard = "relMSE_norm";
  uint32_t candidates = 81;  // the first rung's population
  uint32_t keepOneIn = 3;    // each rung keeps one in this many
  uint32_t rungs = 3;        // the last at the full size and frames
  uint32_t frames = 32;      // frames each configuration runs at the last rung
  uint32_t width = 320, height = 180;
  // The rungs before the last run at half the side per rung down as well as half the frames.
  // Frame times at small sizes carry badly to the full size (fixed costs: the radiance cache's
  // paths, acceleration structures); at the full size every rung costs about 4x more, and one
  // run on cornell chose no better (docs/log/performance.md).
  bool halveSize = true;
  uint64_t seed = 1;
  uint32_t chunk = 8;  // configurations per compare run (beside the baseline)
  // The reference and output options; outDir is the tune's folder. paths/variants are the tune's.
  CompareOptions compare;
};

struct TuneCallbacks {
  std::function<void(Session&, const std::string& sceneFile)> loadScene;  // + the command line's settings
  std::function<void(Session&, const SweepView&)> setView;
  std::function<void(const std::string& line)> log;
  Progress progress;
};

struct TuneOutcome {
  bool complete = false;           // every stage measured and the presets written
  std::string waitingFor;          // else: the stage other shards are still measuring
  size_t measured = 0;             // compare runs this process made
  size_t reused = 0;               // compare runs found done in the folder
  size_t budgetsMissed = 0;        // budgets no configuration met
  nlohmann::json report;           // tune.json, when complete
};

TuneOutcome runTune(Session& session, const SweepPlan& plan, const TuneOptions& options,
                    const std::optional<Shard>& shard, const TuneCallbacks& callbacks);

// How many stages a tune with these options has, each needing the one before it finished: a job
// array per stage (deploy/slurm/submit.sh asks `twinlight tune --print-stage-count`).
uint32_t tuneStageCount(const TuneOptions& options);

// report.html of a finished tune: the front with each point's interval, the chosen points, what
// each budget left off and the images at each chosen point.
void writeTuneReportHtml(const std::filesystem::path& file, const nlohmann::json& tuneReport,
                         const std::filesystem::path& tuneDir);

}  // namespace tl::session
