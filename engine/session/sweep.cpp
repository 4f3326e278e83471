#include "session/sweep.h"

#include "session/image_io.h"
#include "session/json_file.h"
#include "session/provenance.h"
#include "session/report_html.h"
#include "session/sweep_summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace tl::session {
namespace {

constexpr const char* kShardManifest = "shard.json";
constexpr const char* kShardKind = "twinlight compare shard";

nlohmann::json readJson(const std::filesystem::path& file) {
  std::optional<nlohmann::json> j = readJsonFile(file);
  if (!j) throw SessionError(fmt::format("{}: cannot be read", file.string()));
  return std::move(*j);
}

void writeJson(const std::filesystem::path& file, const nlohmann::json& value) { writeTextFile(file, value.dump(2) + "\n"); }

// A one-view sweep without folders is a plain compare: its report is the top-level one.
bool oneReport(const nlohmann::json& views) { return views.size() == 1 && views[0]["dir"].get<std::string>().empty(); }

std::filesystem::path viewDir(const std::filesystem::path& root, const std::string& dir) {
  return dir.empty() ? root : root / dir;
}

// Mean of a figure over the views, null when any view's is missing or non-finite (the mean
// would hide it).
nlohmann::json meanOf(const std::vector<const nlohmann::json*>& entries, const std::string& figure) {
  double sum = 0.0;
  for (const nlohmann::json* e : entries) {
    if (!e->contains(figure) || !(*e)[figure].is_number()) return nullptr;
    sum += (*e)[figure].get<double>();
  }
  const double mean = sum / double(entries.size());
  return std::isfinite(mean) ? nlohmann::json(mean) : nlohmann::json(nullptr);
}

// The sweep's report from its views' report.json files under `root`: written by an
// unsharded run and by a merge alike, so both give the same figures.
nlohmann::json writeSweepReport(const std::filesystem::path& root, const nlohmann::json& grid) {
  static const char* const kFigures[] = {"frameMs", "relMSE", "RMSE", "PSNR", "SSIM", "FLIP", "HDR-FLIP",
                                         "relMSE_norm", "RMSE_norm", "FLIP_norm"};
  nlohmann::json views = nlohmann::json::array();
  std::vector<std::string> order;                                  // configurations, first seen first
  std::map<std::string, std::vector<const nlohmann::json*>> byName;  // a configuration's entry in each view
  std::vector<nlohmann::json> reports;
  for (const auto& v : grid["views"]) reports.push_back(readJson(viewDir(root, v["dir"]) / "report.json"));
  nlohmann::json failures = nlohmann::json::array(), withinNoise = nlohmann::json::array(), limits = nullptr;
  for (size_t i = 0; i < reports.size(); ++i) {
    const nlohmann::json& r = reports[i];
    const nlohmann::json& v = grid["views"][i];
    const std::string dir = v["dir"];
    const std::string prefix = dir.empty() ? "" : dir + "/";
    views.push_back({{"scene", r["scene"]}, {"sceneFile", v["scene"]}, {"camera", v["camera"]}, {"dir", dir},
                     {"report", prefix + "report.json"}, {"html", prefix + "report.html"}, {"device", r["device"]},
                     {"reference", r["reference"]}, {"paths", r["paths"]}});
    for (const auto& p : r["paths"]) {
      const std::string name = p["path"];
      if (!byName.count(name)) order.push_back(name);
      byName[name].push_back(&p);
    }
    if (r.contains("gate")) {
      limits = r["gate"]["failAbove"];
      for (auto f : r["gate"]["failures"]) {
        f["scene"] = r["scene"];
        f["camera"] = v["camera"];
        failures.push_back(f);
      }
      for (auto f : r["gate"].value("withinNoise", nlohmann::json::array())) {
        f["scene"] = r["scene"];
        f["camera"] = v["camera"];
        withinNoise.push_back(f);
      }
    }
  }
  nlohmann::json configurations = nlohmann::json::array();
  for (const std::string& name : order) {
    const auto& entries = byName[name];
    nlohmann::json c = {{"path", name}, {"lightingPath", (*entries[0])["lightingPath"]}, {"views", entries.size()}};
    for (const char* figure : kFigures) c[figure] = meanOf(entries, figure);
    configurations.push_back(c);
  }
  nlohmann::json report = {{"kind", "sweep"},
                           {"twinlight", twinlightJson()},
                           {"grid", grid},
                           {"views", views},
                           {"configurations", configurations},
                           {"means", "each configuration's figures are means over the views that measured it (null when "
                                     "a view's figure is missing); frameMs is a timing, the rest are errors"}};
  if (!reports.empty()) report["forms"] = reports[0]["forms"], report["metrics"] = reports[0]["metrics"];
  if (!limits.is_null())
    report["gate"] = {{"failAbove", limits},
                      {"failures", failures},
                      {"withinNoise", withinNoise},
                      {"passed", failures.empty() && withinNoise.empty()},
                      {"decided", withinNoise.empty() || !failures.empty()}};
  report["summary"] = summarizeSweep(report);
  writeJson(root / "report.json", report);
  writeSweepReportHtml(root / "report.html", report);
  return report;
}

// Copies a view's files from a shard's folder into the merged one (for a one-view sweep the
// folder is the shard's top level, less its manifest).
void copyView(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  std::filesystem::create_directories(to, ec);
  if (ec) throw SessionError(fmt::format("{}: cannot create the folder: {}", to.string(), ec.message()));
  for (const auto& entry : std::filesystem::directory_iterator(from)) {
    if (entry.path().filename() == kShardManifest) continue;
    std::filesystem::copy(entry.path(), to / entry.path().filename(),
                          std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing, ec);
    if (ec)
      throw SessionError(fmt::format("{}: cannot copy into {}: {}", entry.path().string(), to.string(), ec.message()));
  }
}

// "0.1.0 (commit 1a2b3c4d5e6f, modified)" for an error message; a manifest without the field
// was written before shards recorded their build.
std::string buildName(const nlohmann::json& twinlight) {
  if (!twinlight.is_object()) return "an unrecorded build";
  const std::string commit = twinlight.value("commit", nlohmann::json()).is_string()
                                 ? twinlight["commit"].get<std::string>().substr(0, 12)
                                 : std::string("unknown");
  return fmt::format("{} (commit {}{})", twinlight.value("version", std::string("?")), commit,
                     twinlight.value("modified", false) ? ", modified" : "");
}

bool sameFolder(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec) && std::filesystem::equivalent(a, b, ec);
}

}  // namespace

SweepPlan planSweep(const std::vector<std::string>& sceneFiles,
                    const std::function<std::vector<std::string>(const std::string&)>& cameraNames) {
  if (sceneFiles.empty()) throw SessionError("a compare needs a scene");
  std::map<std::string, std::string> stems;
  const bool manyScenes = sceneFiles.size() > 1;
  SweepPlan plan;
  for (const std::string& file : sceneFiles) {
    const std::string stem = std::filesystem::path(file).stem().string();
    if (manyScenes && !stems.emplace(stem, file).second)
      throw SessionError(fmt::format("scenes {} and {} would share the report folder `{}`: give them different file names",
                                     stems[stem], file, stem));
    for (const std::string& camera : cameraNames ? cameraNames(file) : std::vector<std::string>{""}) {
      std::string dir = manyScenes ? stem : "";
      if (!camera.empty()) dir = dir.empty() ? camera : dir + "/" + camera;
      plan.views.push_back({file, camera, dir});
    }
  }
  return plan;
}

nlohmann::json sweepGrid(const SweepPlan& plan, const CompareOptions& o) {
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : plan.views) views.push_back({{"scene", v.sceneFile}, {"camera", v.camera}, {"dir", v.dir}});
  nlohmann::json variants = nlohmann::json::array();
  for (const auto& v : o.variants) variants.push_back({{"name", v.name}, {"path", v.path}, {"settings", v.settings}});
  nlohmann::json gate = nlohmann::json::object();
  for (const auto& t : o.failAbove) gate[t.metric] = t.value;
  return {{"views", views},
          {"paths", o.paths},
          {"variants", variants},
          {"referenceSpp", o.referenceSpp},
          {"referenceNoise", o.referenceNoise ? nlohmann::json(*o.referenceNoise) : nlohmann::json(nullptr)},
          {"referenceNoiseCap", o.referenceNoiseCap},
          {"referenceBounces", o.referenceBounces},
          {"scope", o.scope},
          {"framesPerPath", o.framesPerPath},
          {"referenceFile", o.referenceFile.string()},
          {"failAbove", gate},
          {"settings", plan.settings}};
}

size_t gateFailureCount(const nlohmann::json& report) {
  return report.contains("gate") ? report["gate"]["failures"].size() : 0;
}

size_t gateWithinNoiseCount(const nlohmann::json& report) {
  return report.contains("gate") ? report["gate"].value("withinNoise", nlohmann::json::array()).size() : 0;
}

SweepOutcome runSweep(Session& s, const SweepPlan& plan, const CompareOptions& options, const std::optional<Shard>& shard,
                      const SweepCallbacks& cb) {
  const nlohmann::json grid = sweepGrid(plan, options);
  std::error_code ec;
  std::filesystem::create_directories(options.outDir, ec);
  if (ec) throw SessionError(fmt::format("{}: cannot create the folder: {}", options.outDir.string(), ec.message()));
  // A shard's manifest says it finished: a rerun removes the old one first.
  if (shard) std::filesystem::remove(options.outDir / kShardManifest, ec);

  SweepOutcome outcome;
  nlohmann::json done = nlohmann::json::array();
  std::string loaded;
  for (size_t i = 0; i < plan.views.size(); ++i) {
    if (shard && blockShardOf(i, plan.views.size(), shard->count) != shard->index) continue;
    const SweepView& view = plan.views[i];
    if (loaded != view.sceneFile) {
      cb.loadScene(s, view.sceneFile);
      loaded = view.sceneFile;
    }
    cb.setView(s, view);
    CompareOptions o = options;
    o.outDir = viewDir(options.outDir, view.dir);
    const nlohmann::json report = runCompare(s, o, cb.progress);
    outcome.gateFailures += gateFailureCount(report);
    outcome.gateWithinNoise += gateWithinNoiseCount(report);
    ++outcome.views;
    done.push_back(i);
    if (cb.viewDone) cb.viewDone(view, report);
  }
  if (shard) {
    writeJson(options.outDir / kShardManifest, {{"kind", kShardKind},
                                                {"twinlight", twinlightJson()},
                                                {"shard", {{"index", shard->index}, {"count", shard->count},
                                                           {"source", shard->source}}},
                                                {"views", done},
                                                {"grid", grid}});
  } else if (!oneReport(grid["views"])) {
    outcome.sweepReport = writeSweepReport(options.outDir, grid);
  }
  return outcome;
}

nlohmann::json mergeSweep(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out) {
  if (dirs.empty()) throw SessionError("--merge needs the shards' report folders");
  std::vector<nlohmann::json> manifests;
  for (const auto& dir : dirs) {
    if (sameFolder(dir, out)) throw SessionError(fmt::format("--out {} is one of the shards being merged", out.string()));
    const std::filesystem::path file = dir / kShardManifest;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
      throw SessionError(fmt::format("{}: no {}: not a finished shard of a compare sweep (did its task fail?)", dir.string(),
                                     kShardManifest));
    nlohmann::json m = readJson(file);
    if (!m.is_object() || m.value("kind", "") != kShardKind || !m.contains("grid") || !m.contains("shard") ||
        !m.contains("views"))
      throw SessionError(fmt::format("{}: not a compare shard manifest", file.string()));
    manifests.push_back(std::move(m));
  }
  const nlohmann::json& grid = manifests[0]["grid"];
  const uint32_t count = manifests[0]["shard"]["count"];
  std::map<uint32_t, size_t> byIndex;  // shard index -> position in dirs
  for (size_t k = 0; k < dirs.size(); ++k) {
    const auto& m = manifests[k];
    const uint32_t index = m["shard"]["index"], n = m["shard"]["count"];
    if (m["grid"] != grid)
      throw SessionError(fmt::format("{} is a shard of another sweep than {} (scenes, cameras, configurations or "
                                     "settings differ)",
                                     dirs[k].string(), dirs[0].string()));
    // Shards from two builds would mix figures of two programs in one report (a task rerun
    // after an update is the usual way this happens).
    if (m.value("twinlight", nlohmann::json()) != manifests[0].value("twinlight", nlohmann::json()))
      throw SessionError(fmt::format("{} was measured by twinlight {}, but {} by {}: the shards of one sweep must "
                                     "come from one build (rerun the odd shard)",
                                     dirs[k].string(), buildName(m.value("twinlight", nlohmann::json())),
                                     dirs[0].string(), buildName(manifests[0].value("twinlight", nlohmann::json()))));
    if (n != count)
      throw SessionError(fmt::format("{} is shard {}/{}, but {} is one of {} shards", dirs[k].string(), index, n,
                                     dirs[0].string(), count));
    if (!byIndex.emplace(index, k).second)
      throw SessionError(fmt::format("{} and {} are both shard {}/{}", dirs[byIndex[index]].string(), dirs[k].string(), index,
                                     count));
  }
  if (byIndex.size() != count) {
    std::string missing;
    for (uint32_t i = 0; i < count; ++i)
      if (!byIndex.count(i)) missing += fmt::format("{}{}", missing.empty() ? "" : ", ", i);
    throw SessionError(fmt::format("shard(s) {} of {} missing: merge every shard of the sweep", missing, count));
  }
  // Every view's report is found before anything is copied.
  const nlohmann::json& views = grid["views"];
  std::vector<std::filesystem::path> sources;
  for (size_t v = 0; v < views.size(); ++v) {
    const uint32_t owner = blockShardOf(v, views.size(), count);
    const size_t k = byIndex[owner];
    const auto& held = manifests[k]["views"];
    if (std::find(held.begin(), held.end(), nlohmann::json(v)) == held.end())
      throw SessionError(fmt::format("{} (shard {}/{}) does not hold view {} ({})", dirs[k].string(), owner, count, v,
                                     views[v]["dir"].get<std::string>()));
    sources.push_back(viewDir(dirs[k], views[v]["dir"]));
    std::error_code ec;
    if (!std::filesystem::exists(sources.back() / "report.json", ec))
      throw SessionError(fmt::format("{}: no report.json", sources.back().string()));
  }
  for (size_t v = 0; v < views.size(); ++v) copyView(sources[v], viewDir(out, views[v]["dir"]));
  if (oneReport(views)) return readJson(out / "report.json");
  return writeSweepReport(out, grid);
}

}  // namespace tl::session
