#include "session/tune.h"

#include "session/compare_significance.h"
#include "session/image_io.h"
#include "session/json_file.h"
#include "session/lighting_file.h"
#include "session/presets.h"
#include "session/settings_json.h"
#include "session/tune_space.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <set>
#include <utility>

namespace tl::session {

namespace fs = std::filesystem;

TuneBudget parseTuneBudget(const std::string& text, const std::string& baseline) {
  static const std::regex ratioForm(R"(([0-9]+(\.[0-9]+)?)x-([a-z]+))"), msForm(R"(([0-9]+(\.[0-9]+)?)ms)");
  std::smatch m;
  TuneBudget b{text};
  if (text.size() > 32) throw SessionError(fmt::format("--budget {}...: too long for a budget", text.substr(0, 32)));
  if (std::regex_match(text, m, ratioForm)) {
    if (m[3] != baseline)
      throw SessionError(fmt::format("--budget {}: times are measured against the baseline `{}`: write {}x-{}", text,
                                     baseline, m[1].str(), baseline));
    b.ratio = std::stod(m[1]);
  } else if (std::regex_match(text, m, msForm)) {
    b.ms = std::stod(m[1]);
  } else {
    throw SessionError(fmt::format("--budget {}: give a multiple of the baseline's frame time (1.3x-{}) or a GPU frame "
                                   "time (25ms)", text, baseline));
  }
  if (!(b.ratio > 0.0 || b.ms > 0.0) || !std::isfinite(b.ratio) || !std::isfinite(b.ms) || b.ratio > 1e6 || b.ms > 1e9)
    throw SessionError(fmt::format("--budget {}: the budget must be above 0", text));
  return b;
}

namespace {

// How closely a stage measures: the image's size and the frames each configuration runs.
struct Fidelity {
  uint32_t width = 0, height = 0, frames = 0;
};

Fidelity rungFidelity(const TuneOptions& o, uint32_t rung) {
  const uint32_t down = o.rungs - 1 - rung;
  auto side = [&](uint32_t s) { return o.halveSize ? std::max(16u, s >> down) : s; };
  return {side(o.width), side(o.height), std::max(4u, o.frames >> down)};
}

struct Stage {
  std::string name;  // its folder: rung-0, rung-1, ..., features, features-together
  Fidelity fidelity;
  std::vector<TuneConfig> configs;
};

// One compare run: a chunk of a stage's configurations on one view.
struct Unit {
  size_t view = 0;
  fs::path dir;
  std::vector<TuneConfig> configs;
};

std::vector<Unit> stageUnits(const Stage& stage, const SweepPlan& plan, const TuneOptions& o) {
  std::vector<Unit> units;
  for (size_t v = 0; v < plan.views.size(); ++v) {
    const fs::path viewDir = o.compare.outDir / stage.name / (plan.views[v].dir.empty() ? "view" : plan.views[v].dir);
    for (size_t first = 0, k = 0; first < stage.configs.size(); first += o.chunk, ++k) {
      Unit u{v, viewDir / fmt::format("chunk-{}", k), {}};
      for (size_t i = first; i < std::min(stage.configs.size(), first + o.chunk); ++i) u.configs.push_back(stage.configs[i]);
      units.push_back(std::move(u));
    }
  }
  return units;
}

// A unit's compare report when it has been measured; SessionError when the folder holds a
// measurement of other configurations (another tune wrote it).
std::optional<nlohmann::json> finishedUnit(const Unit& u, const TuneOptions& o) {
  std::optional<nlohmann::json> report = readJsonFile(u.dir / "report.json");
  if (!report) return std::nullopt;
  std::map<std::string, nlohmann::json> measured;
  for (const auto& p : report->value("paths", nlohmann::json::array())) measured[p.value("path", "")] = p.value("overrides", nlohmann::json());
  bool same = measured.count(o.baseline) == 1 && measured.size() == u.configs.size() + 1;
  for (const TuneConfig& c : u.configs) same = same && measured.count(c.name) && measured[c.name] == c.overrides;
  if (!same)
    throw SessionError(fmt::format("{} holds the measurements of another tune: give another --out, or delete it",
                                   u.dir.string()));
  return report;
}

// The path's result in a compare report.
const nlohmann::json* resultOf(const nlohmann::json& report, const std::string& name) {
  for (const auto& p : report["paths"])
    if (p.value("path", "") == name) return &p;
  return nullptr;
}

double number(const nlohmann::json& j, double fallback = std::numeric_limits<double>::infinity()) {
  return j.is_number() ? j.get<double>() : fallback;
}

// One view's point of a configuration: its time over the baseline's in the same run.
TunePoint unitPoint(const nlohmann::json& report, const TuneConfig& c, const std::string& baseline,
                    const std::string& metric, const std::string& guard, const std::string& view) {
  const nlohmann::json* r = resultOf(report, c.name);
  const nlohmann::json* b = resultOf(report, baseline);
  TunePoint p{c.name, c.overrides};
  const double ms = number((*r)["frameMs"]), base = number((*b)["frameMs"]);
  // A median's 95% interval from its frames: its standard error is about 1.253 sigma / sqrt(n),
  // and sigma about the interquartile range / 1.349, so 1.96 * 0.93 * IQR / sqrt(n); the ratio's
  // relative half-width is the two medians' in quadrature.
  auto relativeHalfWidth = [](const nlohmann::json& result, double median) {
    const auto q = result.value("frameMsQuartiles", nlohmann::json::array({median, median}));
    const double n = std::max(1.0, result.value("frames", 1.0));
    return 1.96 * 0.93 * (number(q[1]) - number(q[0])) / (std::sqrt(n) * median);
  };
  if (!(ms > 0.0 && base > 0.0) || !std::isfinite(ms) || !std::isfinite(base))
    throw SessionError(fmt::format("tune: no GPU frame time for {} or {} on this device (timestamps): tune needs them",
                                   c.name, baseline));
  const double half = std::hypot(relativeHalfWidth(*r, ms), relativeHalfWidth(*b, base));
  p.frameMs = ms;
  p.time = ms / base;
  p.timeLow = p.time * std::max(0.0, 1.0 - half);
  p.timeHigh = p.time * (1.0 + half);
  p.error = figureFromJson((*r)["significance"][metric]);
  if (!guard.empty()) p.guard = figureFromJson((*r)["significance"][guard]);
  p.worstView = view;
  return p;
}

// The worst view's figures: a preset for a library of scenes holds for each of them.
TunePoint worstOf(const std::vector<TunePoint>& views) {
  TunePoint w = views.front();
  for (const TunePoint& p : views) {
    if (p.time > w.time) w.time = p.time, w.timeLow = p.timeLow, w.timeHigh = p.timeHigh, w.frameMs = p.frameMs;
    if (!(p.error.value <= w.error.value)) w.error = p.error, w.worstView = p.worstView;
    if (p.guard && w.guard && !(p.guard->value <= w.guard->value)) w.guard = p.guard;
  }
  return w;
}

struct StageResult {
  bool complete = false;
  std::vector<TunePoint> points;   // per configuration, worst over the views
  TunePoint baseline;              // the baseline's own point (time 1), worst over the views
  double baselineMs = 0.0;         // its median frame time, worst view
};

class Tuner {
 public:
  // `loadedScene`: the scene file the session holds already (its settings and lighting as
  // cb.loadScene set them).
  Tuner(Session& s, const SweepPlan& plan, const TuneOptions& o, const std::optional<Shard>& shard, const TuneCallbacks& cb,
        std::string loadedScene)
      : s_(s), plan_(plan), o_(o), shard_(shard), cb_(cb), loadedScene_(std::move(loadedScene)) {}

  // Measures this process's share of the stage; the stage's figures when every unit is done.
  StageResult run(const Stage& stage, TuneOutcome& outcome) {
    const std::vector<Unit> units = stageUnits(stage, plan_, o_);
    std::vector<std::optional<nlohmann::json>> reports(units.size());
    for (size_t i = 0; i < units.size(); ++i) {
      reports[i] = finishedUnit(units[i], o_);
      const bool mine = !shard_ || blockShardOf(i, units.size(), shard_->count) == shard_->index;
      if (reports[i]) {
        outcome.reused += mine ? 1 : 0;
        continue;
      }
      if (!mine) continue;
      log(fmt::format("{}: {} configuration(s) on {} at {}x{}, {} frames", stage.name, units[i].configs.size(),
                      viewName(units[i].view), stage.fidelity.width, stage.fidelity.height, stage.fidelity.frames));
      reports[i] = measure(units[i], stage);
      ++outcome.measured;
    }
    StageResult result;
    if (std::any_of(reports.begin(), reports.end(), [](const auto& r) { return !r; })) return result;
    result.complete = true;
    std::map<std::string, std::vector<TunePoint>> byConfig;
    std::vector<TunePoint> baselineViews;
    for (size_t i = 0; i < units.size(); ++i) {
      const std::string view = viewName(units[i].view);
      for (const TuneConfig& c : units[i].configs) byConfig[c.name].push_back(unitPoint(*reports[i], c, o_.baseline, o_.metric, o_.guard, view));
      baselineViews.push_back(
          unitPoint(*reports[i], {o_.baseline, nlohmann::json::object()}, o_.baseline, o_.metric, o_.guard, view));
      baselineViews.back().name = o_.baseline;
    }
    for (const TuneConfig& c : stage.configs) result.points.push_back(worstOf(byConfig[c.name]));
    result.baseline = worstOf(baselineViews);
    // Its ratio is 1 in every view: its time is the slowest view's (a budget in ms holds there).
    for (const TunePoint& p : baselineViews) result.baselineMs = std::max(result.baselineMs, p.frameMs);
    result.baseline.frameMs = result.baselineMs;
    return result;
  }

 private:
  std::string viewName(size_t v) const {
    const SweepView& view = plan_.views[v];
    return view.dir.empty() ? fs::path(view.sceneFile).stem().string() : view.dir;
  }

  nlohmann::json measure(const Unit& u, const Stage& stage) {
    const SweepView& view = plan_.views[u.view];
    if (loadedScene_ != view.sceneFile) {
      cb_.loadScene(s_, view.sceneFile);
      loadedScene_ = view.sceneFile;
    }
    cb_.setView(s_, view);
    s_.setSize(stage.fidelity.width, stage.fidelity.height);
    CompareOptions c = o_.compare;
    c.paths = {o_.baseline};
    c.variants.clear();
    for (const TuneConfig& config : u.configs) c.variants.push_back({config.name, o_.path, config.overrides});
    c.framesPerPath = stage.fidelity.frames;
    // The error of the last quarter of the frames (at most 8), not of the last one alone: a
    // configuration's own noise (a firefly held for a few frames) widens its interval instead of
    // deciding its rank.
    c.errorFrames = std::clamp(stage.fidelity.frames / 4, 1u, 8u);
    c.outDir = u.dir;
    c.failAbove.clear();
    fs::create_directories(u.dir);
    return runCompare(s_, c, cb_.progress);
  }

  void log(const std::string& line) const {
    if (cb_.log) cb_.log(line);
  }

  Session& s_;
  const SweepPlan& plan_;
  const TuneOptions& o_;
  const std::optional<Shard>& shard_;
  const TuneCallbacks& cb_;
  std::string loadedScene_;
};

// What decides the tune's measurements: a folder resumes only the same tune.
nlohmann::json tunePlanJson(const SweepPlan& plan, const TuneOptions& o) {
  nlohmann::json budgets = nlohmann::json::array();
  for (const TuneBudget& b : o.budgets) budgets.push_back(b.text);
  return {{"grid", sweepGrid(plan, o.compare)},
          {"path", o.path},
          {"baseline", o.baseline},
          {"metric", o.metric},
          {"guard", o.guard},
          {"candidates", o.candidates},
          {"keepOneIn", o.keepOneIn},
          {"rungs", o.rungs},
          {"frames", o.frames},
          {"size", {o.width, o.height}},
          {"halveSize", o.halveSize},
          {"seed", o.seed},
          {"chunk", o.chunk},
          {"budgets", budgets}};
}

void checkOrWritePlan(const fs::path& dir, const nlohmann::json& plan) {
  const fs::path file = dir / "tune-plan.json";
  if (std::optional<nlohmann::json> existing = readJsonFile(file)) {
    if (*existing != plan)
      throw SessionError(fmt::format("{} is another tune's folder (its tune-plan.json differs from these options): give "
                                     "another --out, or the options it was started with", dir.string()));
    return;
  }
  fs::create_directories(dir);
  writeTextFile(file, plan.dump(2) + "\n");
}

// The scenes as they render (geometry, materials, textures and lights, the sidecar's and the
// command line's included): a folder's runs were measured on them, so a scene edited since is
// another tune, refused by name instead of resumed on stale figures. Returns the scene it
// left loaded, so the first measurement on it does not load it again.
std::string checkOrWriteScenes(Session& s, const SweepPlan& plan, const fs::path& dir, const TuneCallbacks& cb) {
  nlohmann::json now = nlohmann::json::object();
  std::string loaded;
  for (const SweepView& view : plan.views) {
    if (now.contains(view.sceneFile)) continue;
    cb.loadScene(s, view.sceneFile);
    loaded = view.sceneFile;
    const std::string lights = lightingJson(s.lighting(), fs::path(view.sceneFile).parent_path());
    now[view.sceneFile] = fmt::format("{:016x}", scene::hashBytes(lights.data(), lights.size(), s.scene().contentHash));
  }
  const fs::path file = dir / "tune-scenes.json";
  if (std::optional<nlohmann::json> measured = readJsonFile(file)) {
    for (const auto& [name, hash] : now.items())
      if (!measured->contains(name) || (*measured)[name] != hash)
        throw SessionError(fmt::format("{}: {} changed since this folder's runs were measured (its geometry, materials "
                                       "or lights): give another --out, or delete the folder",
                                       dir.string(), name));
    return loaded;
  }
  writeTextFile(file, now.dump(2) + "\n");
  return loaded;
}

// The point of a configuration measured in a stage.
const TunePoint& pointNamed(const std::vector<TunePoint>& points, const std::string& name) {
  for (const TunePoint& p : points)
    if (p.name == name) return p;
  throw SessionError("tune: internal: no measurement of " + name);
}

double budgetRatio(const TuneBudget& b, double baselineMs) { return b.ratio > 0.0 ? b.ratio : b.ms / baselineMs; }

// A feature setting's name and off value when the configuration has it on.
struct Feature {
  const lighting::SettingInfo* info;
  double off;
};

std::vector<Feature> featuresOn(const std::vector<TunableSetting>& space, const lighting::RenderSettings& base,
                                const nlohmann::json& overrides) {
  const lighting::RenderSettings settings = applySettingsJson(base, overrides);
  std::vector<Feature> on;
  for (const TunableSetting& t : space)
    if ((t.info->flags & lighting::kSettingFeature) && t.info->get(settings) != featureOffValue(*t.info))
      on.push_back({t.info, featureOffValue(*t.info)});
  return on;
}

std::string budgetFileStem(const TuneOptions& o, const TuneBudget& b) {
  std::string stem = "preset-" + o.path + "-" + b.text;
  for (char& ch : stem)
    if (!(std::isalnum(uint8_t(ch)) || ch == '-' || ch == '_' || ch == '.')) ch = '_';
  return stem;
}

}  // namespace

uint32_t tuneStageCount(const TuneOptions& o) {
  return o.rungs + 2;  // the rungs, then "features" and "features-together"
}

TuneOutcome runTune(Session& session, const SweepPlan& plan, const TuneOptions& o, const std::optional<Shard>& shard,
                    const TuneCallbacks& cb) {
  if (o.budgets.empty()) throw SessionError("tune needs at least one --budget");
  if (o.rungs < 1 || o.rungs > 6 || o.keepOneIn < 2 || o.candidates < 1 || o.candidates > 4096 || o.chunk < 1 ||
      o.frames < 4 || o.width < 16 || o.height < 16)
    throw SessionError("tune: --rungs 1..6, --candidates 1..4096, --frames at least 4, a size of at least 16x16, "
                       "--keep-one-in at least 2");
  const auto& metrics = significanceMetrics();
  for (const std::string& m : {o.metric, o.guard})
    if (!m.empty() && std::find(metrics.begin(), metrics.end(), m) == metrics.end())
      throw SessionError(fmt::format("tune: {} has no interval; one of relMSE, relMSE_norm, FLIP, FLIP_norm", m));
  const std::vector<TunableSetting> space = tunableSettings(o.path);
  if (std::none_of(space.begin(), space.end(), [&](const TunableSetting& t) { return t.info->owner == o.path; }))
    throw SessionError(fmt::format("tune: the `{}` path has no tunable setting of its own", o.path));

  checkOrWritePlan(o.compare.outDir, tunePlanJson(plan, o));
  const std::string loadedScene = checkOrWriteScenes(session, plan, o.compare.outDir, cb);
  TuneOutcome outcome;
  Tuner tuner(session, plan, o, shard, cb, loadedScene);
  auto waiting = [&](const Stage& stage) {
    outcome.waitingFor = stage.name;
    return outcome;
  };

  // The rungs of successive halving.
  std::vector<TuneConfig> configs = samplePopulation(space, o.candidates, o.seed);
  const TuneConfig defaults = configs.front();
  nlohmann::json rungsJson = nlohmann::json::array();
  StageResult last;
  const double widestBudget = [&] {
    double r = 0.0;
    for (const TuneBudget& b : o.budgets) r = std::max(r, b.ratio > 0.0 ? b.ratio : 1e300);
    return r;
  }();
  for (uint32_t rung = 0; rung < o.rungs; ++rung) {
    const Stage stage{fmt::format("rung-{}", rung), rungFidelity(o, rung), configs};
    last = tuner.run(stage, outcome);
    if (!last.complete) return waiting(stage);
    nlohmann::json points = nlohmann::json::array();
    for (const TunePoint& p : last.points) points.push_back(pointJson(p));
    rungsJson.push_back({{"stage", stage.name},
                         {"width", stage.fidelity.width},
                         {"height", stage.fidelity.height},
                         {"frames", stage.fidelity.frames},
                         {"baselineMs", last.baselineMs},
                         {"points", points}});
    if (rung + 1 == o.rungs) break;
    // Budgets in milliseconds keep whatever their ratio is at this rung's size: it is not known
    // at the full size yet, so ms budgets keep every point's chance (no time limit).
    const size_t keep = std::max<size_t>(1, (last.points.size() + o.keepOneIn - 1) / o.keepOneIn);
    std::vector<TunePoint> kept = survivors(last.points, keep, widestBudget * 1.25);
    configs.clear();
    if (std::none_of(kept.begin(), kept.end(), [&](const TunePoint& p) { return p.name == defaults.name; }))
      configs.push_back(defaults);  // the path's defaults: the report's "before"
    for (const TunePoint& p : kept) configs.push_back({p.name, p.overrides});
    std::sort(configs.begin(), configs.end(), [](const TuneConfig& a, const TuneConfig& b) { return a.name < b.name; });
  }
  const std::vector<TunePoint> finalPoints = last.points;
  const std::vector<TunePoint> front = paretoFront(finalPoints);
  const Fidelity full = rungFidelity(o, o.rungs - 1);
  const lighting::RenderSettings base = session.settings();

  // Per budget, the chosen point; then every chosen point without each feature it has on.
  struct Choice {
    TuneBudget budget;
    double limit = 0.0;
    TunePoint chosen;
    bool overBudget = false;  // chosen as the cheapest point, above the budget before its features go
    std::vector<Feature> features;
  };
  std::vector<Choice> choices;
  Stage featureStage{"features", full, {}};
  std::set<std::string> staged;
  for (const TuneBudget& b : o.budgets) {
    Choice c{b, budgetRatio(b, last.baselineMs)};
    if (std::optional<TunePoint> within = chooseWithinBudget(finalPoints, c.limit)) {
      c.chosen = *within;
    } else {
      // Nothing within the budget: the cheapest point (the population is never empty), which
      // may fit once the features the scene does not need are off.
      c.chosen = *std::min_element(finalPoints.begin(), finalPoints.end(),
                                   [](const TunePoint& a, const TunePoint& b) { return a.time < b.time; });
      c.overBudget = true;
    }
    c.features = featuresOn(space, base, c.chosen.overrides);
    if (staged.insert(c.chosen.name).second) {
      featureStage.configs.push_back({c.chosen.name, c.chosen.overrides});
      for (const Feature& f : c.features) {
        nlohmann::json without = c.chosen.overrides;
        without[std::string(f.info->name)] = settingJsonValue(*f.info, f.off);
        featureStage.configs.push_back({c.chosen.name + "-no-" + std::string(f.info->name), without});
      }
    }
    choices.push_back(std::move(c));
  }
  // Every budget has a chosen point: the stage is never empty.
  const StageResult featureResult = tuner.run(featureStage, outcome);
  if (!featureResult.complete) return waiting(featureStage);
  auto featurePoint = [&](const std::string& name) -> const TunePoint& { return pointNamed(featureResult.points, name); };

  // The features each budget can leave off, then all of them off together, checked once more.
  Stage togetherStage{"features-together", full, {}};
  std::map<std::string, std::vector<std::string>> notNeeded;  // chosen name -> features
  for (const Choice& c : choices) {
    if (notNeeded.count(c.chosen.name)) continue;
    const TunePoint& with = featurePoint(c.chosen.name);
    std::vector<std::string>& names = notNeeded[c.chosen.name];
    nlohmann::json together = c.chosen.overrides;
    for (const Feature& f : c.features) {
      const TunePoint& without = featurePoint(c.chosen.name + "-no-" + std::string(f.info->name));
      if (!significantlyMoreAccurate(with, without) && !significantlyFaster(with, without)) {
        names.push_back(std::string(f.info->name));
        together[std::string(f.info->name)] = settingJsonValue(*f.info, f.off);
      }
    }
    if (names.size() > 1) {
      togetherStage.configs.push_back({c.chosen.name, c.chosen.overrides});
      togetherStage.configs.push_back({c.chosen.name + "-lean", together});
    }
  }
  StageResult togetherResult;
  if (!togetherStage.configs.empty()) {
    togetherResult = tuner.run(togetherStage, outcome);
    if (!togetherResult.complete) return waiting(togetherStage);
  }

  // The presets and the report.
  nlohmann::json budgetsJson = nlohmann::json::array();
  for (const Choice& c : choices) {
    nlohmann::json entry = {{"budget", c.budget.text}, {"limitRatio", c.limit}};
    const TunePoint& with = featurePoint(c.chosen.name);
    nlohmann::json overrides = c.chosen.overrides;
    nlohmann::json features = nlohmann::json::array();
    const std::vector<std::string>& names = notNeeded[c.chosen.name];
    // All the unneeded features off together, unless that is significantly worse than the
    // chosen point: then only the one that saves most.
    bool together = names.size() <= 1;
    if (names.size() > 1) {
      const TunePoint& kept = pointNamed(togetherResult.points, c.chosen.name);
      const TunePoint& lean = pointNamed(togetherResult.points, c.chosen.name + "-lean");
      together = !significantlyMoreAccurate(kept, lean);
      entry["leanCheck"] = {{"with", pointJson(kept)}, {"without", pointJson(lean)}, {"heldTogether", together}};
    }
    std::string bestSaver;
    double bestSaving = -1e300;
    for (const Feature& f : c.features) {
      const std::string name(f.info->name);
      const TunePoint& without = featurePoint(c.chosen.name + "-no-" + name);
      const bool unneeded = std::count(names.begin(), names.end(), name) > 0;
      // In the baseline's milliseconds: with and without may come from two compare runs.
      const double saves = (with.time - without.time) * featureResult.baselineMs;
      if (unneeded && saves > bestSaving) bestSaving = saves, bestSaver = name;
      features.push_back({{"setting", name},
                          {"off", settingJsonValue(*f.info, f.off)},
                          {"needed", !unneeded},
                          {"savesMs", saves},
                          {"errorWith", pointJson(with)["error"]},
                          {"errorWithout", pointJson(without)["error"]},
                          {"verdict", unneeded ? (significantlyFaster(without, with) ? "not needed here: off"
                                                                                     : "no effect here: off")
                                               : significantlyMoreAccurate(with, without) ? "needed: the error rises without it"
                                                                                          : "kept: it saves time"}});
    }
    for (auto& f : features) {
      const bool off = !f["needed"].get<bool>() && (together || f["setting"] == bestSaver);
      f["offInPreset"] = off;
      if (off) overrides[f["setting"].get<std::string>()] = f["off"];
    }
    // What the preset itself measured: the lean run, the one feature's run, or the chosen one.
    const TunePoint& presetPoint = names.size() > 1 && together ? pointNamed(togetherResult.points, c.chosen.name + "-lean")
                                   : !bestSaver.empty()         ? featurePoint(c.chosen.name + "-no-" + bestSaver)
                                                                : with;
    const bool met = !c.overBudget || presetPoint.time <= c.limit;
    entry["presetMeasured"] = pointJson(presetPoint);
    entry["chosen"] = pointJson(c.chosen);
    entry["chosenOverBudget"] = c.overBudget;
    entry["features"] = features;
    entry["overrides"] = overrides;
    entry["met"] = met;
    if (met) {
      const fs::path presetFile = o.compare.outDir / (budgetFileStem(o, c.budget) + ".json");
      savePresetFile(presetFile, applySettingsJson(base, overrides));
      entry["preset"] = presetFile.filename().string();
    } else {
      ++outcome.budgetsMissed;
      entry["cheapestRatio"] = std::min(c.chosen.time, presetPoint.time);
    }
    budgetsJson.push_back(entry);
  }
  nlohmann::json frontJson = nlohmann::json::array();
  for (const TunePoint& p : front) frontJson.push_back(pointJson(p));
  nlohmann::json finalJson = nlohmann::json::array();
  TunePoint defaultsPoint;
  for (const TunePoint& p : finalPoints) {
    finalJson.push_back(pointJson(p));
    if (p.name == defaults.name) defaultsPoint = p;
  }
  nlohmann::json space_ = nlohmann::json::array();
  for (const TunableSetting& t : space) {
    nlohmann::json values = nlohmann::json::array();
    for (double v : t.candidates) values.push_back(settingJsonValue(*t.info, v));
    space_.push_back({{"setting", std::string(t.info->name)}, {"candidates", values}});
  }
  size_t renders = 0;
  for (const auto& r : rungsJson) renders += r["points"].size() * plan.views.size();
  outcome.report = {{"kind", "tune"},
                    {"plan", tunePlanJson(plan, o)},
                    {"space", space_},
                    {"rungs", rungsJson},
                    {"final", finalJson},
                    {"front", frontJson},
                    {"defaults", pointJson(defaultsPoint)},
                    {"baseline", pointJson(last.baseline)},
                    {"baselineMs", last.baselineMs},
                    {"budgets", budgetsJson},
                    {"measurements", {{"configurationsMeasured", renders + featureStage.configs.size() * plan.views.size() +
                                                                      togetherStage.configs.size() * plan.views.size()},
                                      {"compareRuns", outcome.measured + outcome.reused}}}};
  outcome.complete = true;
  writeTextFile(o.compare.outDir / "tune.json", outcome.report.dump(2) + "\n");
  writeTuneReportHtml(o.compare.outDir / "report.html", outcome.report, o.compare.outDir);
  return outcome;
}

}  // namespace tl::session
