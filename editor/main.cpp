// `twinlight`: one binary. Without a subcommand it shows the default (or given) scene;
// the headless subcommands work on machines without a display. Errors are one line on
// stderr (`twinlight: error: ...`) and a non-zero exit: 2 when the command line does not
// parse, 3 for a regression gate (compare --fail-above) that failed, 1 for everything else
// (bad values, files, failures at run time, and Vulkan validation errors when the layers are on).
#include "bake_command.h"
#include "bench.h"
#include "compare_cameras.h"
#include "session/capture.h"
#include "cli_args.h"
#include "session/lighting_file.h"
#include "cli_output.h"
#include "editor_app.h"
#include "gpu/install_paths.h"
#include "gpu/renderdoc.h"
#include "gpu/self_test.h"
#include "output_paths.h"
#include "scene/input_limits.h"
#include "session/compare.h"
#include "session/doctor.h"
#include "session/image_io.h"
#include "session/presets.h"
#include "session/settings_json.h"
#include "session/settings_reference.h"
#include "session/shard.h"
#include "session/sweep.h"
#include "session/session.h"
#include "version/version.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

using tl::session::Session;

std::filesystem::path defaultScene() { return tl::gpu::contentDirectory() / "atrium.gltf"; }

struct RenderOptions {
  std::string scene;
  std::string path = "direct";
  std::string size = "640x360";
  uint32_t frames = 1;
  std::vector<std::string> outputs;
  ViewArgs view;
  LightArgs light;
  std::string dumpGraph;
  std::optional<uint32_t> spp;
  std::optional<uint32_t> bounces;
  std::optional<std::string> materials;
  std::optional<float> sunSizeDegrees;
  bool hardShadows = false;
  std::optional<float> rtMeshRatio;
  std::optional<float> rtRaysPerPixel;
  std::optional<bool> rtPretrace;
  std::optional<bool> rtDenoise;
  std::string albedoDb;
  bool allowOutsideFiles = false;
  std::string renderDoc;  // RenderDoc capture path template for one more frame
  double time = 0.0;
  std::optional<double> animateFps;
  // Settings: a file (a settings object, or any JSON Twinlight wrote that records them), then
  // NAME=VALUE assignments; explicit options win over the file.
  std::string settingsFile;
  std::vector<std::string> sets;
  CLI::Option* sizeOption = nullptr;
  bool settingsMayListVariants = false;  // compare: a JSON array is a list of configurations
};

constexpr const char* kMaterialsHelp =
    "material override, every path and the reference: authored (as the scene says), diffuse (Lambert with the "
    "authored base colour and textures: no specular, no normal maps) or clay (Lambert 0.8 grey, no textures)";

// The material override mode by name (one `twinlight: error:` line for anything else).
tl::lighting::MaterialMode parseMaterials(const std::string& name) {
  const auto mode = tl::lighting::parseMaterialMode(name);
  if (!mode) throw tl::session::SessionError(fmt::format("--materials must be authored, diffuse or clay, not `{}`", name));
  return *mode;
}

void addViewAndLightOptions(CLI::App& cmd, RenderOptions& o) {
  o.sizeOption = cmd.add_option("--size", o.size, "image size WxH (wins over --settings)")->capture_default_str();
  cmd.add_option("--set", o.sets,
                 "change a render setting, NAME=VALUE (repeatable; `twinlight settings` lists them), e.g. "
                 "--set shadowMapSize=4096 --set materials=clay; a JSON object is taken too")
      ->allow_extra_args(false);
  cmd.add_option("--settings", o.settingsFile,
                 o.settingsMayListVariants
                     ? "JSON file: settings for every path (an object, or a capture manifest, bench JSON or report "
                       "holding one), or a list of configurations [{\"name\": N, \"path\": P, \"settings\": {...}}, ...] "
                       "measured after --paths"
                     : "JSON file of settings to start from: an object, or a capture manifest, bench JSON or compare "
                       "report (its \"settings\"); --size, --set and the other options win over it");
  cmd.add_option("--materials", o.materials, std::string(kMaterialsHelp) + " [default: authored]");
  cmd.add_option("--camera", o.view.camera, "use the scene's glTF camera N (0-based)");
  cmd.add_option("--albedo-db", o.albedoDb, "albedo database whose baked values and overrides the RT path's hits use");
  cmd.add_flag("--allow-outside-files", o.allowOutsideFiles,
               "let the scene read buffers and images outside its own folder (../, absolute paths, links out)");
  cmd.add_option("--look-from", o.view.lookFrom, "camera position x,y,z (metres, y up)");
  cmd.add_option("--look-at", o.view.lookAt, "point the camera looks at, x,y,z");
  cmd.add_option("--fov", o.view.fovDegrees, "vertical field of view in degrees");
  cmd.add_option("--lighting", o.light.lighting,
                 "lighting file (SCENE.lighting.json: sun, sky, environment, exposure, punctual and area lights) in place of the "
                 "scene's own; the light options below win over it");
  cmd.add_option("--save-lighting", o.light.saveLighting,
                 "write the lighting this command renders with (the scene's lights, --lighting and every light option) "
                 "to a lighting file");
  cmd.add_option("--sun-dir", o.light.sunDir, "direction sunlight travels, x,y,z");
  cmd.add_option("--sun", o.light.sun, "sun irradiance E (W/m^2-like; white Lambertian facing it shows E/pi), E or r,g,b");
  cmd.add_option("--sky", o.light.sky, "uniform sky radiance L, L or r,g,b");
  cmd.add_option("--environment", o.light.environment,
                 "equirectangular environment map (EXR, HDR: radiance on the sky's scale) in place of the uniform sky");
  cmd.add_option("--environment-rotation", o.light.environmentRotation,
                 "turn the environment map about +Y, degrees (counter-clockwise seen from above)");
  cmd.add_option("--environment-intensity", o.light.environmentIntensity, "multiply the environment map's radiance");
  cmd.add_option("--exposure", o.light.exposureEv, "exposure in EV (default: from the sun and sky)");
  cmd.add_option("--sun-size", o.sunSizeDegrees, "angular radius of the sun in degrees (0.27 = the real sun): soft shadows")
      ->check(CLI::Range(0.01f, 10.0f));
  cmd.add_flag("--hard-shadows", o.hardShadows, "3x3 PCF sun shadows instead of PCSS soft shadows");
  cmd.add_option("--rt-mesh-ratio", o.rtMeshRatio, "rt path: triangles of the simplified RT meshes / source triangles (1 = full)")
      ->check(CLI::Range(0.01f, 1.0f));
  cmd.add_option("--rays-per-pixel", o.rtRaysPerPixel,
                 "rt path: 1, 0.5 (a checkerboard alternating each frame) or 0.25 (half resolution: one pixel of each 2x2)")
      ->check(CLI::IsMember({1.0f, 0.5f, 0.25f}));
  cmd.add_option("--pretrace", o.rtPretrace, "rt path: screen-space pre-trace before real rays (true/false)");
  cmd.add_option("--denoise", o.rtDenoise, "rt path: two-pass spatial denoiser after accumulation (true/false)");
  cmd.add_option("--time", o.time, "animation time in seconds (morph targets, node animation) of the first frame")->capture_default_str();
  cmd.add_option("--animate", o.animateFps, "play the animations: each frame advances 1/FPS seconds")
      ->check(CLI::Range(1.0, 1000.0));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

using tl::editor::Progress;

// GPU milliseconds of every frame and pass, gathered over several renderFrames calls.
struct FrameTimes {
  std::vector<double> frames;
  std::vector<std::pair<std::string, std::vector<double>>> passes;

  void add(const Session& session) {
    frames.insert(frames.end(), session.frameGpuMs().begin(), session.frameGpuMs().end());
    for (const auto& [pass, ms] : session.passGpuMs()) {
      auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& p) { return p.first == pass; });
      if (it == passes.end()) it = passes.insert(passes.end(), {pass, {}});
      it->second.insert(it->second.end(), ms.begin(), ms.end());
    }
  }
};

// The first frame compiles pipelines on first use: it is reported apart from the median.
void printFrameTimes(const FrameTimes& times) {
  const auto& frames = times.frames;
  if (frames.empty()) return;
  if (frames.size() == 1) {
    fmt::print("GPU frame time: {:.2f} ms (one frame, includes first-use pipeline compilation)\n", frames[0]);
    return;
  }
  std::vector<double> steady(frames.begin() + 1, frames.end());
  fmt::print("GPU frame time: median {:.2f} ms over {} frames (min {:.2f}, max {:.2f}); first frame {:.2f} ms\n",
             median(steady), steady.size(), *std::min_element(steady.begin(), steady.end()),
             *std::max_element(steady.begin(), steady.end()), frames[0]);
  for (const auto& [pass, ms] : times.passes) {
    std::vector<double> s(ms.begin() + (ms.size() > 1 ? 1 : 0), ms.end());
    fmt::print("  {:24} {:8.2f} ms\n", pass, median(s));
  }
}

// Scene, path, size, settings, view and light from the options every headless subcommand
// shares. Settings in order: defaults, --settings FILE, then the options given explicitly, then
// each --set.
void prepareSession(Session& session, const RenderOptions& o) {
  const std::optional<tl::lighting::MaterialMode> materials =
      o.materials ? std::optional(parseMaterials(*o.materials)) : std::nullopt;
  session.loadScene(o.scene.empty() ? defaultScene() : std::filesystem::path(o.scene),
                    tl::scene::LoadOptions{o.allowOutsideFiles});
  session.setPath(o.path);
  auto [w, h] = parseSize(o.size);
  session.setSize(w, h);
  if (!o.settingsFile.empty()) {
    session.settings() = tl::session::applySettingsJson(session.settings(), tl::session::readSettingsFile(o.settingsFile));
    if (o.sizeOption && o.sizeOption->count() > 0) session.setSize(w, h);
  }
  if (materials) session.settings().materials = *materials;
  if (o.hardShadows) session.settings().softShadows = false;
  if (o.rtMeshRatio) session.settings().rtSimplifyRatio = *o.rtMeshRatio;
  if (o.rtRaysPerPixel) {
    session.settings().rtHalfRays = *o.rtRaysPerPixel == 0.5f;
    session.settings().rtHalfResolution = *o.rtRaysPerPixel == 0.25f;
  }
  if (o.rtPretrace) session.settings().rtPretrace = *o.rtPretrace;
  if (o.rtDenoise) session.settings().rtDenoise = *o.rtDenoise;
  for (const std::string& assignment : o.sets) {
    if (!assignment.empty() && assignment.front() == '{') {  // the JSON form bench --set took first
      nlohmann::json overrides;
      try {
        overrides = tl::session::parseSettingsText(assignment, "--set");
      } catch (const nlohmann::json::exception& e) {
        throw tl::session::SessionError(fmt::format("--set is not JSON: {}", e.what()));
      }
      session.settings() = tl::session::applySettingsJson(session.settings(), overrides);
    } else {
      session.settings() = tl::session::applySettingText(session.settings(), assignment);
    }
  }
  applyView(session, o.view);
  applyLight(session, o.light);
  if (!o.albedoDb.empty()) session.openAlbedoDatabase(o.albedoDb, false);
  if (o.sunSizeDegrees) {
    auto light = session.lighting();
    light.sunAngularRadius = glm::radians(*o.sunSizeDegrees);
    session.setLighting(light);
  }
  if (!o.light.saveLighting.empty()) tl::session::writeLightingFile(o.light.saveLighting, session.lighting());
  session.setAnimationTime(o.time);
  session.setAnimationStep(o.animateFps ? 1.0 / *o.animateFps : 0.0);
}

// One more frame, captured by RenderDoc into `pathTemplate` (RenderDoc appends the frame).
void renderDocFrame(Session& session, const std::filesystem::path& pathTemplate) {
  auto& rd = tl::gpu::RenderDoc::get();
  if (!rd.attached()) throw tl::session::SessionError("RenderDoc capture unavailable: " + rd.unavailableReason());
  rd.setCaptureTemplate(std::filesystem::absolute(pathTemplate).string());
  rd.startFrame(session.device().instance());
  session.renderFrames(1);
  if (!rd.endFrame(session.device().instance()) || rd.captureCount() == 0)
    throw tl::session::SessionError("RenderDoc captured nothing");
  fmt::print("RenderDoc capture: {}\n", rd.capturePath(rd.captureCount() - 1).value_or("?"));
}

int runRender(const RenderOptions& o) {
  // Usage and outputs first, before a device or a scene is touched: a typo costs no render.
  bool sequence = false;
  for (const auto& out : o.outputs) {
    tl::editor::checkImageOutput(out);
    sequence = sequence || tl::editor::isFrameSequence(out);
  }
  if (!o.dumpGraph.empty()) tl::editor::checkGraphOutput(o.dumpGraph);
  if (sequence && !o.animateFps)
    throw UsageError("--out with # writes one image per frame of an animation: add --animate FPS (and --frames N)");
  if (sequence && o.spp) throw UsageError("--spp accumulates one image: it cannot write a --out sequence");
  if (o.frames == 0) throw tl::session::SessionError("--frames must be at least 1");
  if (o.bounces == 0) throw tl::session::SessionError("--bounces must be at least 1");
  uint32_t frames = o.frames;
  if (o.spp) {
    if (*o.spp == 0) throw tl::session::SessionError("--spp must be at least 1");
    if (*o.spp > 16 && *o.spp % 16) throw tl::session::SessionError("--spp must be a multiple of 16, or at most 16");
    frames = (*o.spp + 15) / 16;
  }

  Session session;
  prepareSession(session, o);
  const uint32_t w = session.settings().width, h = session.settings().height;
  if (o.spp && o.path != session.referencePath())
    throw tl::session::SessionError(fmt::format("--spp applies to --path {}", session.referencePath()));
  if (o.bounces) session.settings().referenceBounces = *o.bounces;
  // Up to 16 samples a frame: fewer submissions, and each frame stays short.
  if (o.spp) session.settings().referenceSamplesPerFrame = std::min(*o.spp, 16u);

  FrameTimes times;
  // What each image write said, printed after the progress: the file and, for an EXR beyond
  // the half-float range, that it was written as 32-bit float.
  std::vector<std::string> written;
  auto save = [&](const std::filesystem::path& file) {
    const auto result = session.saveImage(file);
    std::string note;
    if (result.float32)
      note = fmt::format(" (32-bit float: {} of {} pixels exceed the half-float range, 65504, and would have clipped)",
                         result.beyondHalf, result.pixels);
    written.push_back(fmt::format("wrote {}{}", std::filesystem::absolute(file).string(), note));
    if (result.nonFinite > 0)
      throw tl::session::SessionError(
          fmt::format("{}: {} of {} pixels are not finite", file.string(), result.nonFinite, result.pixels));
  };
  auto start = std::chrono::steady_clock::now();
  {
    Progress progress("render");
    auto report = [&](uint32_t done) {
      progress.update(double(done) / frames,
                      o.spp ? fmt::format("{}/{} spp", done * session.settings().referenceSamplesPerFrame, *o.spp)
                            : fmt::format("frame {}/{}", done, frames));
    };
    if (!sequence) {
      session.renderFrames(frames, report);
      times.add(session);
    } else {
      // One frame at a time, each read back and written as it is done: frame_0001 is the first.
      for (uint32_t f = 1; f <= frames; ++f) {
        session.renderFrames(1);
        times.add(session);
        for (const auto& out : o.outputs)
          if (tl::editor::isFrameSequence(out)) save(tl::editor::sequenceFrame(out, f));
        report(f);
      }
    }
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (const auto& out : o.outputs) {
    if (tl::editor::isFrameSequence(out)) continue;
    save(out);
  }
  for (const auto& line : written) fmt::print("{}\n", line);
  if (!o.renderDoc.empty()) renderDocFrame(session, o.renderDoc);
  fmt::print("rendered {} frame(s) of {} with `{}` at {}x{} on {} in {:.2f} s\n", frames, session.scene().name,
             session.path(), w, h, session.device().name(), seconds);
  printFrameTimes(times);
  if (!o.dumpGraph.empty()) {
    if (o.dumpGraph == "-") {
      fmt::print("{}", session.graphDump());
    } else {
      session.writeGraph(o.dumpGraph);  // .dot / .gv: Graphviz
      fmt::print("wrote {}\n", o.dumpGraph);
    }
  }
  return exitStatus(session);
}

// `info --scene FILE`: what the file holds and what of it Twinlight ignores, one line each
// (scene::sceneReport), without a device. Warnings the importer gave are the ignored lines.
int runSceneInfo(const std::string& file) {
  const tl::scene::Scene scene = tl::scene::loadGltf(file);
  fmt::print("scene: {}\n", file);
  for (const auto& line : tl::scene::sceneReport(scene)) fmt::print("{}\n", line);
  for (const auto& w : scene.warnings)
    if (w.find("could not be loaded") != std::string::npos) fmt::print("warning: {}\n", w);
  return 0;
}

// compare --settings FILE as a list: [{"name": N, "path": P, "settings": {...}}, ...].
std::vector<tl::session::CompareVariant> compareVariants(const nlohmann::json& list, const std::string& file) {
  std::vector<tl::session::CompareVariant> variants;
  for (const auto& v : list) {
    if (!v.is_object() || !v.contains("name") || !v.contains("path") || !v["name"].is_string() || !v["path"].is_string())
      throw tl::session::SessionError(fmt::format("{}: each configuration needs \"name\" and \"path\" strings", file));
    variants.push_back({v["name"], v["path"], v.value("settings", nlohmann::json::object())});
  }
  return variants;
}

// The options besides the scene that decide what a compare measures, as given: shards of one
// sweep must have been started with the same ones.
nlohmann::json renderOptionsJson(const RenderOptions& o) {
  auto opt = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"size", o.size},
          {"camera", opt(o.view.camera)},
          {"lookFrom", o.view.lookFrom},
          {"lookAt", o.view.lookAt},
          {"fov", opt(o.view.fovDegrees)},
          {"sunDir", o.light.sunDir},
          {"sun", o.light.sun},
          {"sky", o.light.sky},
          {"exposure", opt(o.light.exposureEv)},
          {"materials", opt(o.materials)},
          {"set", o.sets},
          {"settingsFile", o.settingsFile},
          {"albedoDb", o.albedoDb},
          {"sunSize", opt(o.sunSizeDegrees)},
          {"hardShadows", o.hardShadows},
          {"rtMeshRatio", opt(o.rtMeshRatio)},
          {"raysPerPixel", opt(o.rtRaysPerPixel)},
          {"pretrace", opt(o.rtPretrace)},
          {"denoise", opt(o.rtDenoise)},
          {"time", o.time},
          {"animate", opt(o.animateFps)}};
}

// A report's figure in a column `width` wide with `decimals`, or "-" where the report holds none:
// a figure that is undefined for the view (the PSNR of two equal images, a mean ratio against a
// black reference) is stored as null, and a table shows no "nan".
std::string cell(const nlohmann::json& v, int width, int decimals) {
  if (!v.is_number()) return fmt::format("{:>{}}", "-", width);
  return fmt::format("{:{}.{}f}", v.get<double>(), width, decimals);
}

// One view's figures as tables, and its gate. `failAbove` gives the thresholds' order as the
// user wrote them (a merged report has them only as a JSON object).
void printCompareReport(const nlohmann::json& report, const std::vector<tl::session::GateThreshold>& failAbove) {
  fmt::print("as rendered (linear radiance; SSIM and FLIP of the display images at {:.2f} EV)\n",
             report["exposureEV"].get<double>());
  fmt::print("{:10} {:>9} {:>9} {:>9} {:>8} {:>7} {:>7} {:>9}\n", "path", "GPU ms", "relMSE", "RMSE", "PSNR", "SSIM", "FLIP",
             "HDR-FLIP");
  for (auto& p : report["paths"])
    fmt::print("{:10} {:9.2f} {} {} {} {} {} {}\n", p["path"].get<std::string>(), p["frameMs"].get<double>(),
               cell(p["relMSE"], 9, 4), cell(p["RMSE"], 9, 4), cell(p["PSNR"], 8, 2), cell(p["SSIM"], 7, 4),
               cell(p["FLIP"], 7, 4), cell(p["HDR-FLIP"], 9, 4));
  fmt::print("exposure-normalised (both images x{:.4g}: the reference's mean Y {:.4g} -> 0.18)\n",
             report["reference"]["normalisation"].get<double>(), report["reference"]["meanLuminance"].get<double>());
  fmt::print("{:10} {:>11} {:>11} {:>11} {:>10}\n", "path", "relMSE_norm", "RMSE_norm", "FLIP_norm", "mean ratio");
  for (auto& p : report["paths"])
    fmt::print("{:10} {} {} {} {}\n", p["path"].get<std::string>(), cell(p["relMSE_norm"], 11, 4), cell(p["RMSE_norm"], 11, 4),
               cell(p["FLIP_norm"], 11, 4), cell(p.value("meanRatio", nlohmann::json()), 10, 3));
  fmt::print("per stage (surface pixels)  {:>13} {:>18}\n", "AO abs error", "irradiance relMSE");
  for (auto& p : report["paths"])
    if (p["stages"].contains("ao"))
      fmt::print("{:27} {} {}\n", p["path"].get<std::string>(), cell(p["stages"]["ao"]["meanAbsError"], 13, 4),
                 cell(p["stages"]["irradiance"]["relMSE"], 18, 4));
  const auto& ref = report["reference"];
  if (ref["source"] == "file") {
    fmt::print("reference: {} (external)\n", ref["file"].get<std::string>());
  } else {
    fmt::print("reference: {} spp{}{}\n", ref["spp"].get<int>(), ref["scope"] == "same" ? ", same scope (direct + one bounce)" : "",
               ref["cached"].get<bool>() ? " (reused from the cache)" : "");
    fmt::print("reference bounces: {}\n", ref["bouncePolicy"].get<std::string>());
  }
  fmt::print("materials: {}\n", ref["materials"].get<std::string>());
  // Per bounce: which share of each depth group of the reference each path holds.
  bool anyBounces = false;
  for (auto& p : report["paths"]) anyBounces |= p.contains("bounces") && p["bounces"].contains("groups");
  anyBounces = anyBounces && report["reference"].contains("byDepth");
  if (anyBounces) {
    const auto share = [](const nlohmann::json& v) { return v.is_number() ? fmt::format("{:.1f}%", 100.0 * v.get<double>()) : std::string("-"); };
    std::string header = fmt::format("{:10}", "captured");
    for (auto& g : report["reference"]["byDepth"]["groups"])
      header += fmt::format(" {:>17}", fmt::format("{} ({})", g["group"].get<std::string>(), share(g["shareOfReference"])));
    fmt::print("per bounce (share of each depth group's light a path holds; the group's share of the reference)\n{} {:>8}\n",
               header, "excess");
    for (auto& p : report["paths"]) {
      if (!p.contains("bounces") || !p["bounces"].contains("groups")) continue;
      std::string row = fmt::format("{:10}", p["path"].get<std::string>());
      for (auto& g : p["bounces"]["groups"]) row += fmt::format(" {:>17}", share(g["captured"]));
      fmt::print("{} {:>8}\n", row, share(p["bounces"]["excess"]));
    }
    fmt::print("missing light per bounce (a fraction of the reference's light)\n");
    for (auto& p : report["paths"]) {
      if (!p.contains("bounces") || !p["bounces"].contains("groups")) continue;
      std::string row = fmt::format("{:10}", p["path"].get<std::string>());
      for (auto& g : p["bounces"]["groups"]) row += fmt::format(" {:>17}", share(g["missing"]));
      fmt::print("{}\n", row);
    }
    for (auto& p : report["paths"])
      if (p.contains("bounces") && p["bounces"].contains("summary"))
        fmt::print("{}: {}\n", p["path"].get<std::string>(), p["bounces"]["summary"].get<std::string>());
  }
  if (report.contains("gate")) {
    const auto& gate = report["gate"];
    for (auto& f : gate["failures"])
      fmt::print("gate: FAIL {} {} {} > {}\n", f["path"].get<std::string>(), f["metric"].get<std::string>(),
                 f["value"].is_number() ? fmt::format("{:.4f}", f["value"].get<double>()) : std::string("non-finite"),
                 f["threshold"].get<double>());
    std::string limits;
    if (!failAbove.empty())
      for (const auto& t : failAbove) limits += fmt::format("{}{} <= {}", limits.empty() ? "" : ", ", t.metric, t.value);
    else
      for (auto& [metric, value] : gate["failAbove"].items())
        limits += fmt::format("{}{} <= {}", limits.empty() ? "" : ", ", metric, value.get<double>());
    fmt::print("gate: {} ({})\n", gate["passed"].get<bool>() ? "passed" : "FAILED", limits);
  }
}

// A sweep's configurations: their means over the views.
void printSweepReport(const nlohmann::json& report) {
  fmt::print("== sweep: {} view(s); each configuration's mean over them\n", report["views"].size());
  fmt::print("{:20} {:>9} {:>9} {:>7} {:>11} {:>11}\n", "configuration", "GPU ms", "relMSE", "FLIP", "relMSE_norm", "FLIP_norm");
  for (auto& c : report["configurations"])
    fmt::print("{:20} {} {} {} {} {}\n", c["path"].get<std::string>(), cell(c["frameMs"], 9, 2), cell(c["relMSE"], 9, 4),
               cell(c["FLIP"], 7, 4), cell(c["relMSE_norm"], 11, 4), cell(c["FLIP_norm"], 11, 4));
  if (report.contains("gate"))
    for (auto& f : report["gate"]["failures"])
      fmt::print("gate: FAIL {} {} {} {} {} > {}\n", f["scene"].get<std::string>(), f["camera"].get<std::string>(),
                 f["path"].get<std::string>(), f["metric"].get<std::string>(),
                 f["value"].is_number() ? fmt::format("{:.4f}", f["value"].get<double>()) : std::string("non-finite"),
                 f["threshold"].get<double>());
}

// A failed gate is its own exit code, after every report is written.
int gateExit(size_t failures) {
  if (failures == 0) return 0;
  std::fflush(stdout);  // the figures first, then the error line
  fmt::print(stderr, "twinlight: error: regression gate failed: {} figure(s) above their thresholds\n", failures);
  return 3;
}

int compareMergeCommand(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out) {
  const nlohmann::json report = tl::session::mergeSweep(dirs, out);
  if (report.value("kind", "") == "sweep") printSweepReport(report);
  else printCompareReport(report, {});
  const size_t views = report.value("kind", "") == "sweep" ? report["views"].size() : 1;
  fmt::print("merged {} shard(s): {} view(s) into {}\n", dirs.size(), views,
             (std::filesystem::absolute(out) / "report.html").string());
  return gateExit(tl::session::gateFailureCount(report));
}

int runInfo() {
  Session session;
  auto& d = session.device();
  fmt::print("device: {}\ndriver: {}\nvulkan: {}.{}.{}\n", d.name(), d.driver(), VK_API_VERSION_MAJOR(d.apiVersion()),
             VK_API_VERSION_MINOR(d.apiVersion()), VK_API_VERSION_PATCH(d.apiVersion()));
  if (d.rayTracing().pipeline) {
    auto failure = tl::gpu::rayTracingSelfTest(d);
    fmt::print("ray tracing: {}, self-test {}\n", d.rayTracing().query ? "pipeline + query" : "pipeline",
               failure ? "FAILED: " + *failure : std::string("passed"));
  } else {
    fmt::print("ray tracing: unavailable: {}\n", d.rayTracing().unavailableReason);
  }
  fmt::print("shaders: {}\ncontent: {}\n", tl::gpu::shaderDirectory().string(), tl::gpu::contentDirectory().string());
  fmt::print("lighting paths:\n");
  for (auto& p : session.paths()) {
    std::string caps;
    auto add = [&](bool on, const char* what) {
      if (on) caps += fmt::format("{}{}", caps.empty() ? "" : ", ", what);
    };
    add(p.plugin, "plugin");
    add(p.capabilities.isReference, "reference");
    add(p.capabilities.needsRayTracing, "needs ray tracing");
    add(p.capabilities.accumulates, "accumulates");
    add(!p.capabilities.rasterizes, "traces primary rays");
    add(p.capabilities.halfResolution, "half resolution");
    fmt::print("  {:10} {}{}{}\n", p.name, p.description, caps.empty() ? "" : " (" + caps + ")",
               p.available ? "" : "  [unavailable: " + p.unavailableReason + "]");
  }
  return exitStatus(session);
}

bool hasDisplay() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

}  // namespace

int main(int argc, char** argv) {
  tl::editor::configureLogging(tl::editor::Verbosity::Normal, true);
  CLI::App app{"Twinlight: a lighting lab comparing ray-traced and legacy real-time lighting against a path tracer"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", "twinlight " + tl::versionString());
  // -q / -v before or after the subcommand: each takes them (not a fallthrough, which would
  // also hand a subcommand's stray positional argument to the editor's scene).
  bool quiet = false, verbose = false;
  auto addVerbosityFlags = [&](CLI::App& cmd) {
    auto* quietFlag = cmd.add_flag("-q,--quiet", quiet, "errors only: no warnings, no progress (results still on stdout)");
    cmd.add_flag("-v,--verbose", verbose, "info and debug messages on stderr too")->excludes(quietFlag);
  };
  addVerbosityFlags(app);
  std::string sceneArg, scriptArg, materialsArg = "authored";
  bool headless = false;
  app.add_option("scene", sceneArg, "glTF scene to open (default: content/atrium.gltf)");
  app.add_option("--materials", materialsArg, kMaterialsHelp)->capture_default_str();
  app.add_option("--script", scriptArg, "run editor actions from FILE (see editor/script.h), then quit");
  std::string lightingArg;
  app.add_option("--lighting", lightingArg,
                 "lighting file (SCENE.lighting.json) for the scene, in place of the one File > Save lighting left beside it");
  app.add_flag("--headless", headless, "render the scene to out/ instead of opening the editor");

  RenderOptions render;
  auto* renderCmd = app.add_subcommand("render", "render a scene headless and save the image(s)");
  renderCmd->add_option("--scene", render.scene, "glTF file (.gltf/.glb); default content/atrium.gltf");
  renderCmd->add_option("--path", render.path, "lighting path (`twinlight info` lists them)");
  renderCmd->add_option("--frames", render.frames, "frames to render (the last one is saved)")
      ->check(CLI::Range(1u, kMaxFrames))
      ->capture_default_str();
  renderCmd->add_option("--renderdoc", render.renderDoc,
                        "then capture one more frame with RenderDoc into this path template (run under RenderDoc)");
  renderCmd->add_option("--out", render.outputs,
                        "output image(s): .exr = scene-linear radiance before exposure, .png = tonemapped display")
      ->required();
  renderCmd->add_option("--dump-graph", render.dumpGraph, "write the compiled render graph as text (- for stdout), or Graphviz DOT for a .dot file");
  renderCmd->add_option("--spp", render.spp, "reference path: samples per pixel to accumulate (sets the frames)")
      ->check(CLI::Range(1u, kMaxSpp));
  renderCmd->add_option("--bounces", render.bounces,
                        "reference path: scattering events per path (1 = direct light only, 2 = one indirect bounce)")
      ->check(CLI::Range(1u, kMaxBounces))
      ->capture_default_str();
  addViewAndLightOptions(*renderCmd, render);

  RenderOptions benchRender;
  BenchOptions bench;
  std::string benchJson;
  auto* benchCmd = app.add_subcommand("bench", "per-pass GPU milliseconds (median and spread) as a table and JSON");
  benchCmd->add_option("--scene", benchRender.scene, "glTF file; default content/atrium.gltf");
  benchCmd->add_option("--path", benchRender.path, "lighting path")->capture_default_str();
  benchCmd->add_option("--frames", bench.frames, "frames measured")->check(CLI::Range(1u, kMaxFrames))->capture_default_str();
  benchCmd->add_option("--warmup", bench.warmup, "frames rendered first and left out")
      ->check(CLI::Range(0u, kMaxWarmupFrames))
      ->capture_default_str();
  benchCmd->add_flag("--rays", bench.rays,
                     "rt path: the device's raw ray rate on the scene's TLAS (trivial kernel) against rt.trace's");
  benchCmd->add_flag("--cut-every-frame", bench.cutEveryFrame,
                     "forget the history before every measured frame, as on a camera cut (what rejection costs at worst)");
  benchCmd->add_option("--frames-in-flight", bench.framesInFlight,
                       "frames the host may record ahead of the device: 1 waits for each frame, 2 records the next meanwhile")
      ->check(CLI::Range(1u, tl::gpu::kMaxFramesInFlight))
      ->capture_default_str();
  benchCmd->add_flag("--against-one-in-flight", bench.againstOneInFlight,
                     "also time frames with one in flight against --frames-in-flight, in turns: the wall-clock ratio");
  benchCmd->add_option("--json", benchJson, "write the figures as JSON to FILE (- for stdout)");
  addViewAndLightOptions(*benchCmd, benchRender);

  RenderOptions compareRender;
  compareRender.size = "128x128";
  compareRender.settingsMayListVariants = true;
  tl::session::CompareOptions compare;
  std::string comparePaths, compareOut = "out/compare", compareCache;
  auto* compareCmd = app.add_subcommand("compare", "speed against error of lighting paths versus the reference path tracer");
  std::vector<std::string> compareScenes;
  compareCmd->add_option("--scene", compareScenes,
                         "glTF file(s); several make a sweep with a report per scene (default content/atrium.gltf)");
  compareCmd->add_option("--paths", comparePaths, "comma-separated paths (default: every available one)");
  bool comparePresets = false;
  compareCmd->add_flag("--presets", comparePresets,
                       "measure the built-in presets (Fast, Balanced, Reference-like) of the --paths (default: every "
                       "path, the reference's included) instead of the paths alone");
  compareCmd->add_option("--spp", compare.referenceSpp, "reference samples per pixel (<= 16 or a multiple of 16)")
      ->check(CLI::Range(1u, kMaxSpp))
      ->capture_default_str();
  auto* bouncesOption = compareCmd->add_option("--bounces", compare.referenceBounces, "reference scattering events per path")
                            ->check(CLI::Range(1u, kMaxBounces))
                            ->capture_default_str();
  compareCmd
      ->add_option("--scope", compare.scope,
                   "reference scope: `full` (--bounces events: all the GI) or `same` (direct + one bounce: what the "
                   "real-time paths' rays compute, so their error is not the light they leave out by design)")
      ->check(CLI::IsMember({"full", "same"}))
      ->excludes(bouncesOption)
      ->capture_default_str();
  compareCmd->add_option("--frames", compare.framesPerPath, "frames each path runs before it is measured")
      ->check(CLI::Range(1u, kMaxFrames))
      ->capture_default_str();
  compareCmd->add_option("--out", compareOut, "report directory")->capture_default_str();
  std::string compareCameras;
  compareCmd->add_option("--cameras", compareCameras,
                         "one report per camera: `bookmarks` (the editor's, Ctrl+1..9), `scene` (glTF cameras), "
                         "or a list like 0,b2");
  compareCmd->add_option("--cache", compareCache, "reference cache directory (default: $XDG_CACHE_HOME/twinlight/reference)");
  std::string compareReference, compareFailAbove;
  compareCmd->add_option("--reference", compareReference,
                         "compare against this image (linear RGB EXR from another renderer, same camera and --size) "
                         "instead of rendering the path tracer's");
  compareCmd->add_option("--fail-above", compareFailAbove,
                         "regression gate: exit 3 when any path's figure exceeds its threshold, METRIC=VALUE[,...] "
                         "(relMSE, relMSE_norm, RMSE, RMSE_norm, FLIP, FLIP_norm, HDR-FLIP; e.g. relMSE_norm=0.05,flip=0.1)");
  std::string compareShard;
  std::optional<std::string> compareShardCount;
  std::vector<std::string> compareMerge;
  compareCmd->add_option("--shard", compareShard,
                         "measure only shard i of N of the views (scene x camera), i/N 0-based, or `auto` from a Slurm "
                         "array or Kubernetes Indexed Job; writes shard.json for --merge");
  compareCmd->add_option("--shard-count", compareShardCount,
                         "with --shard auto under a Kubernetes Indexed Job: the shard count (else TWINLIGHT_SHARD_COUNT)");
  compareCmd->add_option("--merge", compareMerge,
                         "assemble the finished shards' report folders into one report in --out (no GPU)");
  addViewAndLightOptions(*compareCmd, compareRender);

  RenderOptions captureRender;
  captureRender.frames = 4;
  std::string captureOut;
  auto* captureCmd = app.add_subcommand("capture", "write every buffer of a frame (EXR + manifest.json) into a folder");
  captureCmd->add_option("--scene", captureRender.scene, "glTF file; default content/atrium.gltf");
  captureCmd->add_option("--path", captureRender.path, "lighting path")->capture_default_str();
  captureCmd->add_option("--frames", captureRender.frames, "frames rendered first (the last is captured)")
      ->check(CLI::Range(1u, kMaxFrames))
      ->capture_default_str();
  captureCmd->add_option("--out", captureOut, "folder to write into")->required();
  bool captureRenderDoc = false;
  captureCmd->add_flag("--renderdoc", captureRenderDoc,
                       "also capture one frame with RenderDoc (run under `renderdoccmd capture` or qrenderdoc)");
  addViewAndLightOptions(*captureCmd, captureRender);

  BakeArgs bake;
  auto* bakeCmd = app.add_subcommand("bake", "bake the per-instance albedo database (or merge or list databases)");
  bakeCmd->add_option("--scene", bake.scenes,
                      "glTF file(s), baked in order into one database (a key they share is baked once); default "
                      "content/atrium.gltf");
  bakeCmd->add_option("--db", bake.db, "the albedo database (SQLite), created when missing")->required();
  bakeCmd->add_option("--shard", bake.shard,
                      "bake only shard i of N (i/N, 0-based): a fixed subset of the keys; or `auto` from a Slurm array "
                      "(SLURM_ARRAY_TASK_ID) or Kubernetes Indexed Job (JOB_COMPLETION_INDEX)");
  bakeCmd->add_option("--shard-count", bake.shardCount,
                      "with --shard auto under a Kubernetes Indexed Job: the shard count (else TWINLIGHT_SHARD_COUNT)");
  bakeCmd->add_option("--batch", bake.batch, "combinations per GPU submission (default: as many as fit, 42)");
  bakeCmd->add_option("--tile", bake.tileSize, "pixels per side of each of the 6 views (part of every key)")->capture_default_str();
  bakeCmd->add_flag("--force", bake.force, "re-bake keys the database already holds");
  bakeCmd->add_flag("--list", bake.list, "print the database's baked entries and overrides, bake nothing");
  bakeCmd->add_option("--merge", bake.merge, "merge these databases into --db (conflicts reported, overrides kept)");
  bakeCmd->add_flag("--allow-outside-files", bake.allowOutsideFiles,
                    "let the scene read buffers and images outside its own folder (../, absolute paths, links out)");

  RenderOptions doctorRender;
  doctorRender.size = "128x72";
  tl::session::DoctorOptions doctor;
  std::string doctorJson;
  auto* doctorCmd = app.add_subcommand(
      "doctor", "stability report: every lighting path on SCENE, NaN/Inf/negative counts per buffer, energy against the "
                "reference, flicker over a short camera orbit, messages from the Vulkan layers; exit status 1 when not healthy");
  doctorCmd->add_option("scene", doctorRender.scene, "glTF file")->required();
  doctorCmd->add_option("--frames", doctor.frames, "frames each real-time path renders before its buffers are read")
      ->check(CLI::Range(1u, kMaxFrames))
      ->capture_default_str();
  doctorCmd->add_option("--spp", doctor.referenceSpp, "the reference's samples per pixel")
      ->check(CLI::Range(1u, kMaxSpp))
      ->capture_default_str();
  doctorCmd->add_option("--orbit-frames", doctor.orbitFrames, "frames of the camera orbit that measures flicker (0: none)")
      ->check(CLI::Range(0u, kMaxFrames))
      ->capture_default_str();
  doctorCmd->add_option("--json", doctorJson, "also write the report as JSON to FILE (- for stdout)");
  addViewAndLightOptions(*doctorCmd, doctorRender);

  bool settingsMarkdown = false, settingsDefaults = false;
  auto* settingsCmd = app.add_subcommand("settings", "list every render setting: owner, default, range, unit, what it restarts");
  settingsCmd->add_flag("--markdown", settingsMarkdown, "as the Markdown table in docs/user-guide.md");
  settingsCmd->add_flag("--json", settingsDefaults, "the defaults as a JSON settings file (for --settings)");

  auto* infoCmd = app.add_subcommand("info", "print the Vulkan device, its ray-tracing support and the lighting paths");
  std::string infoScene;
  infoCmd->add_option("--scene", infoScene,
                      "instead: list what a glTF file holds and every feature of it Twinlight ignores, one line each");

  for (CLI::App* cmd : app.get_subcommands(std::function<bool(CLI::App*)>())) addVerbosityFlags(*cmd);
  // Set after the subcommands are added, which would inherit it: `twinlight --help` alone.
  app.footer(tl::editor::helpFooter());
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    fmt::print(stderr, "twinlight: error: {} (see --help)\n", e.what());
    return 2;
  }
  // Timestamps only in the interactive editor's log; a subcommand or a headless render is a
  // command in a pipeline.
  const bool subcommand = *renderCmd || *benchCmd || *compareCmd || *captureCmd || *bakeCmd || *infoCmd || *doctorCmd;
  const bool editorWindow = !subcommand && !headless && (hasDisplay() || !scriptArg.empty());
  const bool cli = !editorWindow;
  tl::editor::configureLogging(quiet     ? tl::editor::Verbosity::Quiet
                               : verbose ? tl::editor::Verbosity::Verbose
                                         : tl::editor::Verbosity::Normal,
                               cli);
  if (quiet && verbose) {
    fmt::print(stderr, "twinlight: error: -q and -v contradict each other (see --help)\n");
    return 2;
  }

  try {
    if (*renderCmd) return runRender(render);
    if (*infoCmd) return infoScene.empty() ? runInfo() : runSceneInfo(infoScene);
    if (*settingsCmd) {
      if (settingsDefaults) fmt::print("{}\n", tl::session::settingsJson(tl::lighting::RenderSettings{}).dump(2));
      else fmt::print("{}", settingsMarkdown ? tl::session::settingsReferenceMarkdown() : tl::session::settingsReferenceText());
      return 0;
    }
    if (*bakeCmd) return runBake(bake, defaultScene().string());
    if (*captureCmd) {
      tl::session::checkOutputFolder(captureOut);
      if (captureRender.frames == 0) throw tl::session::SessionError("--frames must be at least 1");
      Session session;
      prepareSession(session, captureRender);
      session.requestAllBuffers();
      {
        Progress progress("capture");
        session.renderFrames(captureRender.frames, [&](uint32_t done) {
          progress.update(double(done) / captureRender.frames, fmt::format("frame {}/{}", done, captureRender.frames));
        });
      }
      auto manifest = tl::session::writeCapture(session, captureOut);
      size_t files = 0;
      for (const auto& r : manifest["resources"]) files += !r["file"].is_null();
      fmt::print("captured {} of {} resources of {} / {} (frame {}) into {}\n", files, manifest["resources"].size(),
                 manifest["scene"].get<std::string>(), manifest["lightingPath"].get<std::string>(),
                 manifest["frame"].get<uint64_t>(), captureOut);
      if (captureRenderDoc) renderDocFrame(session, std::filesystem::path(captureOut) / "renderdoc");
      return exitStatus(session);
    }
    if (*compareCmd) {
      // Usage first, before a device or a scene is touched.
      if (!compareFailAbove.empty()) {
        try {
          compare.failAbove = tl::session::parseFailAbove(compareFailAbove);
        } catch (const tl::session::SessionError& e) {
          throw UsageError(e.what());
        }
      }
      if (!compareMerge.empty()) {
        if (!compareShard.empty() || compareShardCount)
          throw UsageError("--merge assembles finished shards: it takes no --shard");
        tl::session::checkOutputFolder(compareOut);
        std::vector<std::filesystem::path> dirs(compareMerge.begin(), compareMerge.end());
        return compareMergeCommand(dirs, compareOut);
      }
      std::optional<tl::session::Shard> shard;
      if (!compareShard.empty() || compareShardCount) {
        if (compareShard.empty()) throw UsageError("--shard-count goes with --shard auto");
        shard = tl::session::resolveShard(compareShard, compareShardCount);
      }
      const std::vector<std::string> scenes = compareScenes.empty() ? std::vector<std::string>{defaultScene().string()}
                                                                    : compareScenes;
      if (!compareReference.empty() && (!compareCameras.empty() || scenes.size() > 1))
        throw UsageError("--reference is one camera's image: it cannot be compared with --cameras or several scenes");
      compare.referenceFile = compareReference;
      std::stringstream list(comparePaths);
      for (std::string p; std::getline(list, p, ',');)
        if (!p.empty()) compare.paths.push_back(p);
      if (comparePresets) {
        // Each preset of the listed paths is a configuration ("rt-Fast"); Balanced is the
        // path at its defaults, so the paths are not measured a second time on their own.
        for (const tl::session::Preset& p : tl::session::builtInPresets())
          if (compare.paths.empty() || std::count(compare.paths.begin(), compare.paths.end(), p.path))
            compare.variants.push_back({p.path + "-" + p.name, p.path, tl::session::presetSettingsJson(p)});
        if (compare.variants.empty()) throw UsageError("--presets: no built-in preset is for the --paths given");
        compare.paths.clear();
      }
      if (!compareRender.settingsFile.empty()) {
        // A list of configurations, or settings every path starts from (prepareSession).
        const nlohmann::json file = tl::session::readSettingsFile(compareRender.settingsFile, true);
        if (file.is_array()) {
          if (comparePresets) throw UsageError("--presets and a --settings list of configurations: give one of them");
          compare.variants = compareVariants(file, compareRender.settingsFile);
          compareRender.settingsFile.clear();
        }
      }
      compare.cacheDir = compareCache;
      compare.outDir = compareOut;
      tl::session::checkOutputFolder(compareOut);

      tl::session::SweepPlan plan = tl::session::planSweep(
          scenes, compareCameras.empty() ? std::function<std::vector<std::string>(const std::string&)>()
                                         : [&](const std::string& file) {
                                             return tl::editor::compareCameraNames(file, compareCameras);
                                           });
      plan.settings = renderOptionsJson(compareRender);
      if (shard)
        fmt::print("shard {}/{} ({}) of a sweep of {} view(s)\n", shard->index, shard->count, shard->source,
                   plan.views.size());
      const bool headers = plan.views.size() > 1 || !plan.views[0].dir.empty();
      tl::session::SweepCallbacks callbacks;
      callbacks.loadScene = [&](Session& s, const std::string& file) {
        RenderOptions o = compareRender;
        o.scene = file;
        prepareSession(s, o);
      };
      callbacks.setView = [&](Session& s, const tl::session::SweepView& view) {
        // Every view starts from the scene's own camera and the command line's view options:
        // the same whichever views this process measured before.
        if (!s.scene().cameras.empty()) s.useSceneCamera(0);
        else s.fitViewToScene();
        applyView(s, compareRender.view);
        if (!view.camera.empty()) tl::editor::useCompareCamera(s, view.camera);
        if (headers) fmt::print("== {}\n", view.dir);
      };
      callbacks.viewDone = [&](const tl::session::SweepView& view, const nlohmann::json& report) {
        printCompareReport(report, compare.failAbove);
        fmt::print("wrote {}\n", (std::filesystem::absolute(compareOut) / view.dir / "report.html").lexically_normal().string());
      };
      Progress progress("compare");
      callbacks.progress = [&](const std::string& what, double f) { progress.update(f, what); };
      Session session;
      const tl::session::SweepOutcome outcome = tl::session::runSweep(session, plan, compare, shard, callbacks);
      if (shard) {
        fmt::print("shard {}/{}: measured {} of {} view(s) into {}; `twinlight compare --merge` the shards' folders\n",
                   shard->index, shard->count, outcome.views, plan.views.size(),
                   std::filesystem::absolute(compareOut).string());
        // The merge's exit code carries the gate: a failing shard would keep a scheduler's
        // dependent merge job from running.
        if (outcome.gateFailures) fmt::print("gate: {} figure(s) above their thresholds (the merge fails)\n", outcome.gateFailures);
        return exitStatus(session);
      }
      if (outcome.sweepReport) {
        printSweepReport(*outcome.sweepReport);
        fmt::print("wrote {} reports and {}\n", outcome.views, (std::filesystem::absolute(compareOut) / "report.html").string());
      }
      // Validation errors first (the figures are not trusted then), then the gate.
      if (int status = exitStatus(session); status != 0) return status;
      return gateExit(outcome.gateFailures);
    }
    if (*doctorCmd) {
      tl::editor::checkJsonOutput(doctorJson);
      // The validation layers are part of the report: they are always on here.
      tl::gpu::DeviceOptions device;
      device.validation = true;
      Session session(device);
      prepareSession(session, doctorRender);
      const auto report = tl::session::runDoctor(session, doctor);
      // With the JSON on stdout, stdout is that one document: the text report goes to stderr.
      fmt::print(doctorJson == "-" ? stderr : stdout, "{}", report.toText());
      if (doctorJson == "-") {
        fmt::print("{}\n", report.toJson().dump(2));
      } else if (!doctorJson.empty()) {
        tl::session::writeTextFile(doctorJson, report.toJson().dump(2) + "\n");
        fmt::print("wrote {}\n", doctorJson);
      }
      if (!report.healthy())
        throw tl::session::SessionError(fmt::format("{} is not healthy: non-finite or negative values or validation "
                                                    "messages (the report above names them)",
                                                    doctorRender.scene));
      return 0;
    }
    if (*benchCmd) {
      tl::editor::checkJsonOutput(benchJson);
      if (bench.frames == 0) throw tl::session::SessionError("--frames must be at least 1");
      Session session;
      prepareSession(session, benchRender);
      if (bench.frames == 0) throw tl::session::SessionError("--frames must be at least 1");
      nlohmann::json report;
      {
        Progress progress("bench");
        report = runBench(session, bench, [&](const std::string& what, double f) { progress.update(f, what); });
      }
      // With the JSON on stdout, stdout is that one document: the table goes to stderr.
      if (benchJson == "-") {
        if (tl::editor::verbosity() != tl::editor::Verbosity::Quiet) fmt::print(stderr, "{}", benchTable(report));
        fmt::print("{}\n", report.dump(2));
      } else {
        fmt::print("{}", benchTable(report));
      }
      if (!benchJson.empty() && benchJson != "-") {
        tl::session::writeTextFile(benchJson, report.dump(2) + "\n");
        fmt::print("wrote {}\n", benchJson);
      }
      return exitStatus(session);
    }
    // No subcommand: the main job on the default (or given) scene. The interactive editor
    // needs a display; without one the scene is rendered headless.
    const tl::lighting::MaterialMode materials = parseMaterials(materialsArg);
    if (editorWindow) {
      std::optional<std::filesystem::path> scene, script;
      if (!sceneArg.empty()) scene = sceneArg;
      if (!scriptArg.empty()) script = scriptArg;
      std::optional<std::filesystem::path> lighting;
      if (!lightingArg.empty()) lighting = lightingArg;
      tl::editor::EditorApp editor(scene, script, materials, lighting);
      return editor.run();
    }
    RenderOptions o;
    o.scene = sceneArg;
    o.materials = materialsArg;
    o.light.lighting = lightingArg;
    std::filesystem::path stem = sceneArg.empty() ? defaultScene().stem() : std::filesystem::path(sceneArg).stem();
    o.outputs = {(std::filesystem::path("out") / (stem.string() + ".png")).string(),
                 (std::filesystem::path("out") / (stem.string() + ".exr")).string()};
    fmt::print("no display found (DISPLAY/WAYLAND_DISPLAY unset); rendering {} headless\n", stem.string());
    return runRender(o);
  } catch (const UsageError& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 2;
  } catch (const tl::session::ShardError& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "twinlight: error: {}\n", e.what());
    return 1;
  }
}
