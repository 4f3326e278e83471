// `twinlight compare`: speed against error of lighting paths versus the reference path tracer,
// on one view or a sweep of scenes and cameras (sharded, then merged).
#include "cli_command.h"
#include "compare_tables.h"
#include "render_options.h"

#include "cli_output.h"
#include "compare_cameras.h"
#include "session/image_io.h"
#include "session/presets.h"
#include "session/settings_json.h"
#include "session/shard.h"
#include "session/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

namespace tl::editor {
namespace {

using session::Session;

// compare --settings FILE as a list: [{"name": N, "path": P, "settings": {...}}, ...].
std::vector<session::CompareVariant> compareVariants(const nlohmann::json& list, const std::string& file) {
  std::vector<session::CompareVariant> variants;
  for (const auto& v : list) {
    if (!v.is_object() || !v.contains("name") || !v.contains("path") || !v["name"].is_string() || !v["path"].is_string())
      throw session::SessionError(fmt::format("{}: each configuration needs \"name\" and \"path\" strings", file));
    variants.push_back({v["name"], v["path"], v.value("settings", nlohmann::json::object())});
  }
  return variants;
}

// The accuracy goals a sweep's summary missed (session/sweep_summary.h), for --goals.
size_t missedGoals(const nlohmann::json& report) {
  size_t missed = 0;
  if (report.contains("summary"))
    for (const auto& g : report["summary"]["goals"]) missed += g.value("held", true) ? 0 : 1;
  return missed;
}

// With --goals, a missed accuracy goal is a failed gate too.
int goalsExit(const nlohmann::json* report, bool goals) {
  if (!goals || !report) return 0;
  const size_t missed = missedGoals(*report);
  if (missed == 0) return 0;
  std::fflush(stdout);
  fmt::print(stderr, "twinlight: error: {} accuracy goal(s) missed (the summary above says which)\n", missed);
  return 3;
}

int compareMergeCommand(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out, bool goals) {
  const nlohmann::json report = session::mergeSweep(dirs, out);
  if (report.value("kind", "") == "sweep") printSweepReport(report);
  else printCompareReport(report, {});
  const size_t views = report.value("kind", "") == "sweep" ? report["views"].size() : 1;
  fmt::print("merged {} shard(s): {} view(s) into {}\n", dirs.size(), views,
             (std::filesystem::absolute(out) / "report.html").string());
  if (int status = gateExit(session::gateFailureCount(report), session::gateWithinNoiseCount(report)); status != 0)
    return status;
  return goalsExit(&report, goals);
}

class CompareCommand : public CliCommand {
 public:
  CompareCommand() {
    render_.size = "128x128";
    render_.settingsMayListVariants = true;
  }

  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("compare", "speed against error of lighting paths versus the reference path tracer");
    cmd->add_option("--scene", scenes_,
                    "glTF file(s); several make a sweep with a report per scene (default content/atrium.gltf)");
    cmd->add_option("--paths", paths_, "comma-separated paths (default: every available one)");
    cmd->add_flag("--presets", presets_,
                  "measure the built-in presets (Fast, Balanced, Reference-like) of the --paths (default: every "
                  "path, the reference's included) instead of the paths alone");
    spp_ = cmd->add_option("--spp", compare_.referenceSpp,
                           "reference samples per pixel (<= 16 or a multiple of 16); with --reference-noise, the cap")
               ->check(CLI::Range(1u, kMaxSpp))
               ->capture_default_str();
    cmd->add_option("--reference-noise", compare_.referenceNoise,
                    fmt::format("render the reference until its relative standard error (the root of the mean variance "
                                "of the pixels' estimates over their mean) is at most this, e.g. 0.01, instead of a fixed "
                                "--spp, which then caps it (default {} samples a pixel)",
                                session::NoiseTarget::kDefaultMaxSamples));
    auto* bounces = cmd->add_option("--bounces", compare_.referenceBounces, "reference scattering events per path")
                        ->check(CLI::Range(1u, kMaxBounces))
                        ->capture_default_str();
    cmd->add_option("--scope", compare_.scope,
                    "reference scope: `full` (--bounces events: all the GI) or `same` (direct + one bounce: what the "
                    "real-time paths' rays compute, so their error is not the light they leave out by design)")
        ->check(CLI::IsMember({"full", "same"}))
        ->excludes(bounces)
        ->capture_default_str();
    cmd->add_option("--frames", compare_.framesPerPath, "frames each path runs before it is measured")
        ->check(CLI::Range(1u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--out", out_, "report directory")->capture_default_str();
    cmd->add_option("--cameras", cameras_,
                    "one report per camera: `bookmarks` (the editor's, Ctrl+1..9), `scene` (glTF cameras), "
                    "or a list like 0,b2");
    cmd->add_option("--cache", cache_, "reference cache directory (default: $XDG_CACHE_HOME/twinlight/reference)");
    cmd->add_option("--reference", reference_,
                    "compare against this image (linear RGB EXR from another renderer, same camera and --size) "
                    "instead of rendering the path tracer's");
    cmd->add_option("--fail-above", failAbove_,
                    "regression gate: exit 3 when any path's figure exceeds its threshold, METRIC=VALUE[,...] "
                    "(relMSE, relMSE_norm, RMSE, RMSE_norm, FLIP, FLIP_norm, HDR-FLIP; e.g. relMSE_norm=0.05,flip=0.1)");
    cmd->add_option("--shard", shard_,
                    "measure only shard i of N of the views (scene x camera), i/N 0-based, or `auto` from a Slurm "
                    "array or Kubernetes Indexed Job; writes shard.json for --merge");
    cmd->add_option("--shard-count", shardCount_,
                    "with --shard auto under a Kubernetes Indexed Job: the shard count (else TWINLIGHT_SHARD_COUNT)");
    cmd->add_option("--merge", merge_, "assemble the finished shards' report folders into one report in --out (no GPU)");
    cmd->add_flag("--goals", goals_,
                  "a sweep of several views: exit 3 when the share of views meeting an accuracy goal is below its "
                  "target (rt mean within 10% on 95%, rt relMSE_norm <= 0.5x legacy's on 90%, legacy mean within 35% "
                  "on 90%, dark views dark in every path; the summary table lists them)");
    addViewAndLightOptions(*cmd, render_);
    return cmd;
  }

  int run() override {
    // Usage first, before a device or a scene is touched.
    if (!failAbove_.empty()) {
      try {
        compare_.failAbove = session::parseFailAbove(failAbove_);
      } catch (const session::SessionError& e) {
        throw UsageError(e.what());
      }
    }
    if (!merge_.empty()) {
      if (!shard_.empty() || shardCount_) throw UsageError("--merge assembles finished shards: it takes no --shard");
      session::checkOutputFolder(out_);
      std::vector<std::filesystem::path> dirs(merge_.begin(), merge_.end());
      return compareMergeCommand(dirs, out_, goals_);
    }
    std::optional<session::Shard> shard;
    if (!shard_.empty() || shardCount_) {
      if (shard_.empty()) throw UsageError("--shard-count goes with --shard auto");
      shard = session::resolveShard(shard_, shardCount_);
    }
    const std::vector<std::string> scenes = scenes_.empty() ? std::vector<std::string>{defaultScene().string()} : scenes_;
    if (!reference_.empty() && (!cameras_.empty() || scenes.size() > 1))
      throw UsageError("--reference is one camera's image: it cannot be compared with --cameras or several scenes");
    compare_.referenceFile = reference_;
    if (compare_.referenceNoise) {
      if (!reference_.empty()) throw UsageError("--reference-noise is the path tracer's: it cannot go with --reference");
      if (spp_->count() > 0) compare_.referenceNoiseCap = compare_.referenceSpp;
    }
    chooseConfigurations();
    compare_.cacheDir = cache_;
    compare_.outDir = out_;
    session::checkOutputFolder(out_);

    session::SweepPlan plan = session::planSweep(
        scenes, cameras_.empty() ? std::function<std::vector<std::string>(const std::string&)>()
                                 : [&](const std::string& file) { return compareCameraNames(file, cameras_); });
    plan.settings = renderOptionsJson(render_);
    if (shard)
      fmt::print("shard {}/{} ({}) of a sweep of {} view(s)\n", shard->index, shard->count, shard->source, plan.views.size());
    Progress progress("compare");
    Session session;
    const session::SweepOutcome outcome = session::runSweep(session, plan, compare_, shard, callbacks(plan, progress));
    if (shard) {
      fmt::print("shard {}/{}: measured {} of {} view(s) into {}; `twinlight compare --merge` the shards' folders\n",
                 shard->index, shard->count, outcome.views, plan.views.size(), std::filesystem::absolute(out_).string());
      // The merge's exit code carries the gate: a failing shard would keep a scheduler's
      // dependent merge job from running.
      if (outcome.gateFailures) fmt::print("gate: {} figure(s) above their thresholds (the merge fails)\n", outcome.gateFailures);
      return exitStatus(session);
    }
    if (outcome.sweepReport) {
      printSweepReport(*outcome.sweepReport);
      fmt::print("wrote {} reports and {}\n", outcome.views, (std::filesystem::absolute(out_) / "report.html").string());
    }
    // Validation errors first (the figures are not trusted then), then the gate.
    if (int status = exitStatus(session); status != 0) return status;
    if (int status = gateExit(outcome.gateFailures, outcome.gateWithinNoise); status != 0) return status;
    return goalsExit(outcome.sweepReport ? &*outcome.sweepReport : nullptr, goals_);
  }

 private:
  // The paths, presets or --settings list of configurations to measure.
  void chooseConfigurations() {
    std::stringstream list(paths_);
    for (std::string p; std::getline(list, p, ',');)
      if (!p.empty()) compare_.paths.push_back(p);
    if (presets_) {
      // Each preset of the listed paths is a configuration ("rt-Fast"); Balanced is the
      // path at its defaults, so the paths are not measured a second time on their own.
      for (const session::Preset& p : session::builtInPresets())
        if (compare_.paths.empty() || std::count(compare_.paths.begin(), compare_.paths.end(), p.path))
          compare_.variants.push_back({p.path + "-" + p.name, p.path, session::presetSettingsJson(p)});
      if (compare_.variants.empty()) throw UsageError("--presets: no built-in preset is for the --paths given");
      compare_.paths.clear();
    }
    if (!render_.settingsFile.empty()) {
      // A list of configurations, or settings every path starts from (prepareSession).
      const nlohmann::json file = session::readSettingsFile(render_.settingsFile, true);
      if (file.is_array()) {
        if (presets_) throw UsageError("--presets and a --settings list of configurations: give one of them");
        compare_.variants = compareVariants(file, render_.settingsFile);
        render_.settingsFile.clear();
      }
    }
  }

  session::SweepCallbacks callbacks(const session::SweepPlan& plan, Progress& progress) {
    const bool headers = plan.views.size() > 1 || !plan.views[0].dir.empty();
    session::SweepCallbacks c;
    c.loadScene = [this](Session& s, const std::string& file) {
      RenderOptions o = render_;
      o.scene = file;
      prepareSession(s, o);
    };
    c.setView = [this, headers](Session& s, const session::SweepView& view) {
      // Every view starts from the scene's own camera and the command line's view options:
      // the same whichever views this process measured before.
      if (!s.scene().cameras.empty()) s.useSceneCamera(0);
      else s.fitViewToScene();
      applyView(s, render_.view);
      if (!view.camera.empty()) useCompareCamera(s, view.camera);
      if (headers) fmt::print("== {}\n", view.dir);
    };
    c.viewDone = [this](const session::SweepView& view, const nlohmann::json& report) {
      printCompareReport(report, compare_.failAbove);
      fmt::print("wrote {}\n", (std::filesystem::absolute(out_) / view.dir / "report.html").lexically_normal().string());
    };
    c.progress = [&progress](const std::string& what, double f) { progress.update(f, what); };
    return c;
  }

  RenderOptions render_;
  session::CompareOptions compare_;
  CLI::Option* spp_ = nullptr;
  std::vector<std::string> scenes_;
  std::string paths_, out_ = "out/compare", cache_, cameras_, reference_, failAbove_, shard_;
  bool goals_ = false;
  bool presets_ = false;
  std::optional<std::string> shardCount_;
  std::vector<std::string> merge_;
};

}  // namespace

std::unique_ptr<CliCommand> makeCompareCommand() { return std::make_unique<CompareCommand>(); }

}  // namespace tl::editor
