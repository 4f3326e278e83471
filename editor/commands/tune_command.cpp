// `twinlight tune`: the cheapest settings of a lighting path that the scenes need, found against
// the reference (session/tune.h), as a preset per budget.
#include "cli_command.h"
#include "render_options.h"

#include "cli_output.h"
#include "compare_cameras.h"
#include "session/image_io.h"
#include "session/json_file.h"
#include "session/shard.h"
#include "session/tune.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include <unistd.h>

namespace tl::editor {
namespace {

using session::Session;

// Copies the finished measurements of other tune folders (shards that did not share one) into
// `out`: every compare report folder under a stage, and the plan, which must agree.
int tuneMergeCommand(const std::vector<std::string>& dirs, const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  // A folder that holds a tune takes only that tune's runs.
  std::optional<nlohmann::json> plan = session::readJsonFile(out / "tune-plan.json");
  size_t copied = 0;
  for (const std::string& d : dirs) {
    const fs::path dir(d);
    const std::optional<nlohmann::json> dirPlan = session::readJsonFile(dir / "tune-plan.json");
    if (!dirPlan) throw session::SessionError(fmt::format("{}: not a tune folder (no tune-plan.json)", d));
    if (plan && *plan != *dirPlan)
      throw session::SessionError(fmt::format("{}: the plan of another tune than the folders before it (or --out's)", d));
    plan = dirPlan;
    const fs::path outAbsolute = fs::weakly_canonical(out), dirAbsolute = fs::weakly_canonical(dir);
    if (outAbsolute == dirAbsolute || outAbsolute.string().rfind(dirAbsolute.string() + "/", 0) == 0)
      throw session::SessionError(fmt::format("--out {} lies in {}: merge into another folder", out.string(), d));
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (entry.path().filename() != "report.json" || entry.path().parent_path() == dir) continue;
      const fs::path folder = entry.path().parent_path(), target = out / fs::relative(folder, dir);
      if (fs::exists(target / "report.json")) continue;
      fs::create_directories(target);
      for (const auto& file : fs::directory_iterator(folder))
        if (file.path().filename() != "report.json") fs::copy_file(file.path(), target / file.path().filename(), fs::copy_options::overwrite_existing);
      // report.json marks the run done: it arrives whole or not at all.
      session::writeFileAtomically(target / "report.json", [&](const std::string& tmp) {
        return fs::copy_file(folder / "report.json", tmp, fs::copy_options::overwrite_existing);
      });
      ++copied;
    }
  }
  if (!fs::exists(out / "tune-plan.json")) session::writeTextFile(out / "tune-plan.json", plan->dump(2) + "\n");
  fmt::print("merged {} measurement(s) from {} folder(s) into {}; run the tune again with --out {} to go on\n", copied,
             dirs.size(), fs::absolute(out).string(), out.string());
  return 0;
}

class TuneCommand : public CliCommand {
 public:
  TuneCommand() {
    render_.size = "320x180";
    tune_.compare.referenceSpp = 256;
  }

  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand(
        "tune", "the cheapest settings of a lighting path that the scenes need, found against the reference: a preset per budget");
    cmd->add_option("--scene", scenes_, "glTF file(s); several give one preset that holds for all (the worst view decides)");
    cmd->add_option("--path", tune_.path, "the lighting path whose settings are searched")->capture_default_str();
    cmd->add_option("--baseline", tune_.baseline, "the path whose frame time is the unit of time, measured beside every run")
        ->capture_default_str();
    cmd->add_option("--budget", budgets_,
                    "frame-time budget(s): a multiple of the baseline's frame time (1.3x-legacy) or a GPU frame time "
                    "(25ms); a preset each (default 1x-legacy)");
    cmd->add_option("--metric", tune_.metric, "the error to minimise: FLIP_norm, FLIP, relMSE_norm or relMSE")->capture_default_str();
    cmd->add_option("--guard", tune_.guard,
                    "a second error that must not get significantly worse than the chosen point's (FLIP barely sees "
                    "a firefly, relMSE rewards losing light where that removes fireflies), or `none`")
        ->capture_default_str();
    cmd->add_option("--candidates", tune_.candidates, "configurations drawn for the first rung (the defaults among them)")
        ->check(CLI::Range(1u, 4096u))
        ->capture_default_str();
    cmd->add_option("--keep-one-in", tune_.keepOneIn, "each rung keeps one configuration in this many")
        ->check(CLI::Range(2u, 64u))
        ->capture_default_str();
    cmd->add_option("--rungs", tune_.rungs, "rungs of successive halving; each before the last at half the side and frames")
        ->check(CLI::Range(1u, 6u))
        ->capture_default_str();
    cmd->add_flag_callback("--full-size-rungs", [this] { tune_.halveSize = false; },
                  "every rung at the full size (only the frames halved): frame times that carry to the full size, "
                  "at about 4x the cost of the first rungs");
    cmd->add_option("--frames", tune_.frames, "frames each configuration runs at the last rung")
        ->check(CLI::Range(4u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--seed", tune_.seed, "seed of the drawn configurations (the same seed, the same population)")
        ->capture_default_str();
    cmd->add_option("--spp", tune_.compare.referenceSpp, "reference samples per pixel (<= 16 or a multiple of 16)")
        ->check(CLI::Range(1u, kMaxSpp))
        ->capture_default_str();
    cmd->add_option("--chunk", tune_.chunk, "configurations per compare run (a shard's unit of work)")
        ->check(CLI::Range(1u, 256u))
        ->capture_default_str();
    cmd->add_option("--cameras", cameras_, "views per scene: `bookmarks`, `scene` (glTF cameras) or a list like 0,b2");
    cmd->add_option("--cache", cache_, "reference cache directory (default: $XDG_CACHE_HOME/twinlight/reference)");
    cmd->add_option("--out", out_, "the tune's folder (resumes what it holds)")->capture_default_str();
    cmd->add_option("--shard", shard_,
                    "measure only shard i of N of each stage, i/N 0-based or `auto` (Slurm, Kubernetes); the shards "
                    "share --out and run once per stage");
    cmd->add_option("--shard-count", shardCount_, "with --shard auto under a Kubernetes Indexed Job: the shard count");
    cmd->add_option("--merge", merge_, "copy the measurements of tune folders that shards wrote apart into --out (no GPU)");
    cmd->add_flag("--print-stage-count", printStageCount_,
                  "print how many stages these options make (a job array each, one after another) and exit: "
                  "the options are checked, nothing is measured");
    cmd->add_flag("--stop-with-parent", stopWithParent_,
                  "stop (exit 1, the folder resumable) when the process that started this one ends: the editor "
                  "starts its tunes so");
    addViewAndLightOptions(*cmd, render_);
    return cmd;
  }

  int run() override {
    if (!merge_.empty()) {
      if (!shard_.empty() || shardCount_) throw UsageError("--merge copies finished measurements: it takes no --shard");
      session::checkOutputFolder(out_);
      return tuneMergeCommand(merge_, out_);
    }
    if (scenes_.empty() && !printStageCount_) throw UsageError("tune needs --scene (or --merge)");
    if (budgets_.empty()) budgets_ = {"1x-" + tune_.baseline};
    if (tune_.guard == "none" || tune_.guard == tune_.metric) tune_.guard.clear();
    try {
      for (const std::string& b : budgets_) tune_.budgets.push_back(session::parseTuneBudget(b, tune_.baseline));
    } catch (const session::SessionError& e) {
      throw UsageError(e.what());
    }
    for (const auto& [option, name] : {std::pair{"--path", tune_.path}, std::pair{"--baseline", tune_.baseline}})
      if (name == "reference") throw UsageError(fmt::format("{} reference: the reference is what tune measures against", option));
    if (tune_.compare.referenceSpp > 16 && tune_.compare.referenceSpp % 16 != 0)
      throw UsageError(fmt::format("--spp {}: give at most 16 or a multiple of 16", tune_.compare.referenceSpp));
    if (printStageCount_) {
      fmt::print("{}\n", session::tuneStageCount(tune_));
      return 0;
    }
    std::optional<session::Shard> shard;
    if (!shard_.empty() || shardCount_) {
      if (shard_.empty()) throw UsageError("--shard-count goes with --shard auto");
      shard = session::resolveShard(shard_, shardCount_);
    }
    auto [w, h] = parseSize(render_.size);
    tune_.width = w, tune_.height = h;
    tune_.compare.cacheDir = cache_;
    tune_.compare.outDir = out_;
    session::checkOutputFolder(out_);
    session::SweepPlan plan = session::planSweep(
        scenes_, cameras_.empty() ? std::function<std::vector<std::string>(const std::string&)>()
                                  : [&](const std::string& file) { return compareCameraNames(file, cameras_); });
    plan.settings = renderOptionsJson(render_);

    Progress progress("tune");
    session::TuneCallbacks cb;
    cb.loadScene = [this](Session& s, const std::string& file) {
      RenderOptions o = render_;
      o.scene = file;
      o.path = tune_.path;
      prepareSession(s, o);
    };
    cb.setView = [this](Session& s, const session::SweepView& view) {
      if (!s.scene().cameras.empty()) s.useSceneCamera(0);
      else s.fitViewToScene();
      applyView(s, render_.view);
      if (!view.camera.empty()) useCompareCamera(s, view.camera);
    };
    cb.log = [](const std::string& line) {
      fmt::print("{}\n", line);
      std::fflush(stdout);
    };
    // Checked with every progress step (each frame of a compare run): a tune whose editor died
    // stops within a frame instead of measuring on for nobody.
    const pid_t parent = getppid();
    cb.progress = [&progress, parent, this](const std::string& what, double f) {
      if (stopWithParent_ && getppid() != parent)
        throw session::SessionError(fmt::format(
            "the process that started this tune (pid {}) has ended: stopped; the same command resumes it", parent));
      progress.update(f, what);
    };
    Session session;
    // The base settings come from the first scene's command-line settings (presets hold them).
    cb.loadScene(session, plan.views.front().sceneFile);
    // Both paths must run here before the folder is claimed (a typo would lock it otherwise).
    session.setPath(tune_.baseline);
    session.setPath(tune_.path);
    const session::TuneOutcome outcome = session::runTune(session, plan, tune_, shard, cb);
    progress.finish();
    if (!outcome.complete) {
      fmt::print("tune: measured {} run(s) ({} found done); stage `{}` waits for other shards: run the tune again "
                 "(same options, same --out) once they finish\n",
                 outcome.measured, outcome.reused, outcome.waitingFor);
      return exitStatus(session);
    }
    printOutcome(outcome);
    if (int status = exitStatus(session); status != 0) return status;
    if (outcome.budgetsMissed && shard) {
      // A scheduler's dependent job must still start: the unmet budgets are in the report.
      fmt::print("tune: {} budget(s) met by no configuration (a shard finished the tune: exit 0)\n", outcome.budgetsMissed);
      return 0;
    }
    if (outcome.budgetsMissed) {
      std::fflush(stdout);
      fmt::print(stderr, "twinlight: error: {} budget(s) met by no configuration (listed above)\n", outcome.budgetsMissed);
      return 1;
    }
    return 0;
  }

 private:
  // "FLIP_norm 0.0651 [0.0622, 0.0681], relMSE_norm 0.0838 [0.0399, 0.128]": the error and its guard.
  std::string errors(const nlohmann::json& point) const {
    auto one = [](const std::string& name, const nlohmann::json& e) {
      return fmt::format("{} {:.4g} [{:.4g}, {:.4g}]", name, e["value"].get<double>(), e["low"].get<double>(), e["high"].get<double>());
    };
    std::string text = one(tune_.metric, point["error"]);
    if (!tune_.guard.empty() && point["guard"].is_object()) text += ", " + one(tune_.guard, point["guard"]);
    return text;
  }

  void printOutcome(const session::TuneOutcome& outcome) const {
    const nlohmann::json& t = outcome.report;
    fmt::print("tune of {} against {} ({} defaults: {:.2f} ms): {} compare run(s) ({} found done), front of {} "
               "configuration(s)\n",
               tune_.path, tune_.baseline, tune_.baseline, t["baselineMs"].get<double>(), outcome.measured + outcome.reused,
               outcome.reused, t["front"].size());
    const auto& d = t["defaults"];
    fmt::print("  {} defaults: {:.2f}x, {}; {}: {}\n", tune_.path, d["timeRatio"].get<double>(), errors(d), tune_.baseline,
               errors(t["baseline"]));
    for (const auto& b : t["budgets"]) {
      const auto& c = b["chosen"];
      fmt::print("  budget {}: {} at {:.2f}x{}, {}\n", b["budget"].get<std::string>(), c["name"].get<std::string>(),
                 c["timeRatio"].get<double>(),
                 b["chosenOverBudget"].get<bool>() ? " (the cheapest point: none was within the budget)" : "", errors(c));
      for (const auto& f : b["features"])
        fmt::print("    {}: {}{}, saves {:.2f} ms\n", f["setting"].get<std::string>(), f["verdict"].get<std::string>(),
                   f["offInPreset"].get<bool>() || f["needed"].get<bool>() ? "" : " (kept: off together they were worse)",
                   f["savesMs"].get<double>());
      const auto& m = b["presetMeasured"];
      // The preset significantly worse than the baseline's defaults, by the error or the guard.
      auto worseOn = [&](const char* figure) {
        return m[figure].is_object() && t["baseline"][figure].is_object() &&
               m[figure]["low"].get<double>() > t["baseline"][figure]["high"].get<double>();
      };
      std::string worseText;
      if (worseOn("error")) worseText = tune_.metric;
      if (worseOn("guard")) worseText += (worseText.empty() ? "" : " and ") + tune_.guard;
      const bool worse = !worseText.empty();
      if (b["met"].get<bool>())
        fmt::print("    preset: {:.2f}x, {}{} -> {}\n", m["timeRatio"].get<double>(), errors(m),
                   worse ? fmt::format(" ({} worse than {}'s defaults)", worseText, tune_.baseline) : "",
                   (std::filesystem::absolute(out_) / b["preset"].get<std::string>()).string());
      else
        fmt::print("    no preset: the cheapest measured ran at {:.2f}x\n", b["cheapestRatio"].get<double>());
    }
    fmt::print("wrote {}\n", (std::filesystem::absolute(out_) / "report.html").string());
  }

  RenderOptions render_;
  session::TuneOptions tune_;
  std::vector<std::string> scenes_, budgets_, merge_;
  bool stopWithParent_ = false;
  bool printStageCount_ = false;
  std::string cameras_, cache_, out_ = "out/tune", shard_;
  std::optional<std::string> shardCount_;
};

}  // namespace

std::unique_ptr<CliCommand> makeTuneCommand() { return std::make_unique<TuneCommand>(); }

}  // namespace tl::editor
