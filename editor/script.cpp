#include "script.h"

#include "editor_app.h"
#include "script_lights.h"
#include "settings_panel.h"
#include "ui_helpers.h"
#include "gpu/install_paths.h"
#include "session/capture.h"
#include "session/capture_encoding.h"
#include "session/settings_json.h"
#include "gpu/formats.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <ctime>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

namespace tl::editor {
namespace {

double cpuSeconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
double threadCpuSeconds() { return cpuSeconds(CLOCK_THREAD_CPUTIME_ID); }
double processCpuSeconds() { return cpuSeconds(CLOCK_PROCESS_CPUTIME_ID); }

}  // namespace

Script::Script(const std::filesystem::path& file) : file_(file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the script", file.string()));
  std::string line;
  while (std::getline(in, line)) lines_.push_back(line);
}

void Script::fail(EditorApp& app, const std::string& why) {
  failure_ = fmt::format("{}:{}: {}", file_.string(), next_, why);
  app.requestQuit();
}

namespace {

// A key by name: F1..F12, A..Z, 0..9, Enter, Escape, Tab, Backspace, Delete, Up, Down.
std::optional<int> keyCode(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0]))) return GLFW_KEY_A + (std::toupper(name[0]) - 'A');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0]))) return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F' && std::isdigit(static_cast<unsigned char>(name[1]))) {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  static const std::map<std::string, int> named = {{"Enter", GLFW_KEY_ENTER},   {"Escape", GLFW_KEY_ESCAPE},
                                                   {"Tab", GLFW_KEY_TAB},       {"Backspace", GLFW_KEY_BACKSPACE},
                                                   {"Delete", GLFW_KEY_DELETE}, {"Up", GLFW_KEY_UP},
                                                   {"Down", GLFW_KEY_DOWN}};
  auto it = named.find(name);
  return it == named.end() ? std::nullopt : std::optional<int>(it->second);
}

}  // namespace

void Script::step(EditorApp& app) {
  if (failed()) return;
  if (app.input().pending()) return;  // injected input reaches the interface first
  if (measureFrames_ > 0) {
    if (--measureFrames_ == 0) {
      double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count() -
                       measureSeconds_;
      const uint64_t frames = app.uiFrames() - measureStart_, engine = app.engineFramesDone() - measureEngineStart_;
      const uint64_t presented = app.framesPresented() - measurePresentedStart_;
      const uint64_t superseded = app.framesSuperseded() - measureSupersededStart_;
      const double cpu = threadCpuSeconds() - measureCpu_, processCpu = processCpuSeconds() - measureProcessCpu_;
      const auto& compare = app.compareView();
      const std::string path = compare ? fmt::format("compare {} | {}", compare->left, compare->right) : app.session().path();
      // The UI's frame rate is its loop's: every pass takes the input and runs the panels.
      // Presented frames are the passes that drew the window (what changed on screen).
      fmt::print("editor: UI loop {:.1f} fps over {} passes, window presented {:.1f} fps ({} frames; {} replaced "
                 "by a newer one before drawn), engine {:.2f} fps ({} frames), frame on screen {:.0f} ms old, "
                 "UI thread {:.1f} ms CPU a pass, process {:.0f}% of a core, render {}x{}, path {}, {}\n",
                 double(frames) / seconds, frames, double(presented) / seconds, presented, superseded,
                 double(engine) / seconds, engine, 1000.0 * app.shownFrameAge(),
                 1000.0 * cpu / double(std::max<uint64_t>(frames, 1)), 100.0 * processCpu / seconds,
                 app.session().settings().width, app.session().settings().height, path, app.session().device().name());
      // Where the frames went: the UI thread's wall time by phase, then CPU by thread group
      // (the engine's threads run at a lower priority and are marked so), per UI frame.
      const FrameProfile& p = app.frameProfile();
      const double perFrame = 1000.0 / double(std::max<uint64_t>(frames, 1));
      fmt::print("editor: a UI pass's wall time: input {:.1f} ms, panels {:.1f} ms, present {:.1f} ms, pacing sleep {:.1f} ms\n",
                 perFrame * (p.input - measureProfile_.input), perFrame * (p.panels - measureProfile_.panels),
                 perFrame * (p.present - measureProfile_.present), perFrame * (p.sleep - measureProfile_.sleep));
      std::vector<std::pair<double, std::string>> threads;
      for (const auto& [group, cpuNow] : threadCpuByGroup()) {
        auto before = measureThreads_.find(group);
        const double used = cpuNow - (before == measureThreads_.end() ? 0.0 : before->second);
        if (used > 0.0) threads.push_back({used, group});
      }
      std::sort(threads.rbegin(), threads.rend());
      std::string list;
      for (const auto& [used, group] : threads) list += fmt::format("{}{} {:.1f}", list.empty() ? "" : ", ", group, perFrame * used);
      double load[3] = {};
      std::ifstream("/proc/loadavg") >> load[0] >> load[1] >> load[2];
      fmt::print("editor: CPU ms a UI pass by thread: {}; machine load {:.1f} on {} CPUs\n", list, load[0],
                 std::thread::hardware_concurrency());
    }
    return;
  }
  // `wait N`: N engine frames finish (N UI frames when the engine has nothing to render).
  if (waitFrames_ > 0) {
    if (app.engineActive() ? app.engineFramesDone() < waitUntil_ : --waitFrames_ > 0) return;
    waitFrames_ = 0;
  }
  if (waitScreenshot_) {
    if (app.screenshotPending()) return;
    waitScreenshot_ = false;
  }
  if (waitCapture_) {
    if (app.frameCapturePending()) return;
    waitCapture_ = false;
  }
  if (waitLoaded_) {
    if (app.loading()) return;
    waitLoaded_ = false;
  }
  if (!waitShaderError_.empty()) {
    std::vector<std::string> errors = app.shaderReloader() ? app.shaderReloader()->errors() : std::vector<std::string>{};
    auto hit = std::find_if(errors.begin(), errors.end(), [&](auto& e) { return e.find(waitShaderError_) != std::string::npos; });
    if (hit == errors.end()) {
      if (++shaderErrorFrames_ > 120) return fail(app, fmt::format("no shader error containing `{}`", waitShaderError_));
      return;
    }
    fmt::print("script: shader error reported: {}\n", *hit);
    waitShaderError_.clear();
  }
  if (reloadWaiting_) {
    if (app.sceneReloads() == reloadsAtCopy_ || app.loading()) {
      const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - reloadWaitStart_).count();
      if (waited > 60.0) return fail(app, "the scene was not reloaded within 60 s of its file changing");
      return;
    }
    reloadWaiting_ = false;
    const glm::dvec3 now = app.cameraView().position;
    if (glm::length(now - cameraAtCopy_) > 1e-6)
      return fail(app, fmt::format("the reload moved the camera from {:.3f},{:.3f},{:.3f} to {:.3f},{:.3f},{:.3f}",
                                   cameraAtCopy_.x, cameraAtCopy_.y, cameraAtCopy_.z, now.x, now.y, now.z));
    fmt::print("script: the scene reloaded; the camera stayed at {:.3f},{:.3f},{:.3f}\n", now.x, now.y, now.z);
  }
  if (waitBake_) {
    if (app.albedoBake()) return;
    waitBake_ = false;
    fmt::print("script: albedo bake {}\n", app.lastBakeSummary());
  }
  if (capture_ != Capture::None) {
    if (app.viewportCapture().empty()) {
      // The engine's next frame brings it (a slow path takes a while).
      if (++captureWaitFrames_ > 6000) return fail(app, "the viewport could not be read back");
      return;
    }
    if (capture_ == Capture::Snapshot) {
      snapshot_ = app.viewportCapture();
    } else {
      const auto& now = app.viewportCapture();
      if (now.size() != snapshot_.size()) return fail(app, "the viewport changed size since the snapshot");
      double diff = 0.0;
      for (size_t i = 0; i < now.size(); ++i) diff += std::abs(now[i] - snapshot_[i]);
      diff /= double(now.size());
      if (diff < changedAtLeast_)
        return fail(app, fmt::format("the viewport did not change (mean difference {:.4f}, at least {:g} expected)", diff,
                                     changedAtLeast_));
      fmt::print("script: the viewport changed (mean difference {:.3f})\n", diff);
    }
    capture_ = Capture::None;
  }
  while (next_ < lines_.size()) {
    std::string line = lines_[next_++];
    std::istringstream in(line);
    std::string cmd;
    if (!(in >> cmd) || cmd[0] == '#') continue;
    std::string arg;
    std::getline(in >> std::ws, arg);
    try {
      if (cmd == "open") {
        std::filesystem::path p = arg;
        if (p.is_relative() && !std::filesystem::exists(p)) p = gpu::contentDirectory().parent_path() / p;  // "content/x.gltf"
        app.openScene(p);
        waitLoaded_ = true;
      } else if (cmd == "wait-loaded") {
        waitLoaded_ = true;
      } else if (cmd == "path") {
        app.session().setPath(arg);
        app.settings().lightingPath = arg;
      } else if (cmd == "click") {
        float x, y;
        if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) return fail(app, "click needs X Y");
        app.clickViewport({x, y});
      } else if (cmd == "click-viewport") {
        float u, v;
        if (std::sscanf(arg.c_str(), "%f %f", &u, &v) != 2) return fail(app, "click-viewport needs U V");
        app.clickViewport(app.viewportMin() + app.viewportSize() * glm::vec2(u, v));
      } else if (cmd == "select") {
        const auto& inst = app.session().scene().instances;
        auto it = std::find_if(inst.begin(), inst.end(), [&](auto& i) { return i.name == arg; });
        if (it == inst.end()) return fail(app, fmt::format("no instance called `{}`", arg));
        app.select(uint32_t(it - inst.begin()));
      } else if (cmd == "expect-selected") {
        std::string got = app.selected() ? app.session().scene().instances[*app.selected()].name : "none";
        if (got != arg) return fail(app, fmt::format("expected `{}` to be selected, but `{}` is", arg, got));
        fmt::print("script: `{}` is selected\n", got);
      } else if (cmd == "preview") {
        app.pinPreview(arg == "final" ? "" : arg);
      } else if (cmd == "render-scale") {
        app.settings().renderScale = std::clamp(std::stof(arg), 0.1f, 2.0f);
      } else if (cmd == "help") {
        app.showHelp(arg == "on");
      } else if (cmd == "browser") {
        app.showBrowser(arg == "on");
      } else if (cmd == "wait") {
        waitFrames_ = std::max(0, std::stoi(arg));
        // Frames begun from now on: one in flight was begun with what came before this line.
        waitUntil_ = app.engineFramesBegun() + uint64_t(waitFrames_);
        return;
      } else if (cmd == "measure") {
        measureFrames_ = std::max(1, std::stoi(arg));
        measureStart_ = app.uiFrames();
        measurePresentedStart_ = app.framesPresented();
        measureSupersededStart_ = app.framesSuperseded();
        measureEngineStart_ = app.engineFramesDone();
        measureCpu_ = threadCpuSeconds();
        measureProcessCpu_ = processCpuSeconds();
        measureThreads_ = threadCpuByGroup();
        measureProfile_ = app.frameProfile();
        measureSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
        return;
      } else if (cmd == "screenshot") {
        app.requestScreenshot(arg);
        waitScreenshot_ = true;
        return;  // taken by the window's thread: the script goes on once it is written
      } else if (cmd == "snapshot" || cmd == "expect-viewport-changed") {
        if (cmd == "expect-viewport-changed" && snapshot_.empty()) return fail(app, "no snapshot to compare with");
        capture_ = cmd == "snapshot" ? Capture::Snapshot : Capture::Compare;
        // A noisy path changes by its noise alone: its test names a larger difference.
        changedAtLeast_ = cmd == "snapshot" || arg.empty() ? 0.01 : std::atof(arg.c_str());
        if (!(changedAtLeast_ > 0.0)) return fail(app, "expect-viewport-changed takes a mean difference above 0");
        captureWaitFrames_ = 0;
        app.requestViewportCapture();
        return;
      } else if (cmd == "capture") {
        app.requestFrameCapture(arg.empty() ? app.defaultCaptureFolder() : std::filesystem::path(arg));
        waitCapture_ = true;
        return;  // written after the next engine frame
      } else if (cmd == "albedo-db") {
        app.openAlbedoDatabase(arg);
      } else if (cmd == "albedo-impact") {
        app.session().captureAlbedoBaseline();
        app.pinPreview("albedo.impact");
      } else if (cmd == "albedo-bake") {
        app.startAlbedoBake(false);
        waitBake_ = true;
        return;
      } else if (cmd == "albedo-override" || cmd == "albedo-undo" || cmd == "albedo-redo" || cmd == "albedo-save" ||
                 cmd == "expect-albedo-source") {
        auto& lib = app.session().albedo();
        if (!app.selected()) return fail(app, cmd + " needs a selected instance");
        const uint32_t c = lib.combinationOf(*app.selected());
        if (cmd == "albedo-override") {
          glm::vec3 rgb;
          if (std::sscanf(arg.c_str(), "%f %f %f", &rgb.r, &rgb.g, &rgb.b) != 3) return fail(app, "albedo-override needs R G B");
          lib.setOverride(c, rgb);
        } else if (cmd == "albedo-undo") {
          if (!lib.undo()) return fail(app, "nothing to undo");
        } else if (cmd == "albedo-redo") {
          if (!lib.redo()) return fail(app, "nothing to redo");
        } else if (cmd == "albedo-save") {
          lib.save();
        } else {
          std::string got = albedo::sourceName(lib.entries()[c].source);
          if (got != arg) return fail(app, fmt::format("expected albedo source `{}`, but it is `{}`", arg, got));
          fmt::print("script: albedo source is `{}`\n", got);
        }
      } else if (cmd == "undo" || cmd == "redo") {
        const std::string did = cmd == "undo" ? app.undo() : app.redo();
        if (did.empty()) return fail(app, "nothing to " + cmd);
        fmt::print("script: {}\n", did);
      } else if (cmd == "preset") {
        applyNamedPreset(app, arg);
      } else if (cmd == "save-preset") {
        fmt::print("script: wrote preset {}\n", saveNamedPreset(app, arg).string());
      } else if (cmd == "expect-scene-warnings") {
        const auto& warnings = app.session().scene().warnings;
        if (std::to_string(warnings.size()) != arg)
          return fail(app, fmt::format("expected {} scene warning(s), but there are {}", arg, warnings.size()));
        if (!warnings.empty() && !app.scenePanelOpen()) return fail(app, "the Scene panel is not open");
        fmt::print("script: {} scene warning(s)\n", warnings.size());
        for (const auto& w : warnings) fmt::print("script: warning: {}\n", w);
      } else if (cmd == "expect-scene-report") {
        // A line of the Scene panel's report (what `twinlight info --scene` prints) holds `arg`.
        if (!app.scenePanelOpen()) return fail(app, "the Scene panel is not open");
        const auto& report = app.sceneReport();
        const auto line =
            std::find_if(report.begin(), report.end(), [&](const std::string& l) { return l.find(arg) != std::string::npos; });
        if (line == report.end()) return fail(app, fmt::format("no line of the scene report holds `{}`", arg));
        fmt::print("script: scene report: {}\n", *line);
      } else if (cmd == "expect-orphans") {
        const auto& lib = app.session().albedo();
        if (std::to_string(lib.orphanCount()) != arg)
          return fail(app, fmt::format("expected {} orphaned override(s), but there are {}", arg, lib.orphanCount()));
        fmt::print("script: {} orphaned override(s)\n", lib.orphanCount());
        for (const auto& o : lib.orphans())
          if (!o.removed)
            fmt::print("script: orphan `{}` {:.3f} {:.3f} {:.3f}: {}\n", o.label, o.rgb.r, o.rgb.g, o.rgb.b,
                       albedo::orphanReason(o));
      } else if (cmd == "orphan-reapply" || cmd == "orphan-delete") {
        auto& lib = app.session().albedo();
        std::istringstream words(arg);
        size_t index = 0;
        std::string target;
        if (!(words >> index)) return fail(app, cmd + " needs the orphan's number (0 = the first listed)");
        words >> target;
        // The index among those listed (not removed), as the Albedo panel shows them.
        std::optional<size_t> orphan;
        for (size_t i = 0, listed = 0; i < lib.orphans().size() && !orphan; ++i)
          if (!lib.orphans()[i].removed && listed++ == index) orphan = i;
        if (!orphan) return fail(app, fmt::format("there is no orphaned override {} ({} listed)", index, lib.orphanCount()));
        if (cmd == "orphan-delete") {
          lib.deleteOrphan(*orphan);
        } else if (target == "selected") {
          if (!app.selected()) return fail(app, "orphan-reapply N selected needs a selected instance");
          lib.reapplyOrphan(*orphan, lib.combinationOf(*app.selected()));
        } else if (target.empty()) {
          const auto same = lib.orphans()[*orphan].sameLabel;
          if (!same) return fail(app, fmt::format("`{}` has no new key (no combination with its name)", lib.orphans()[*orphan].label));
          lib.reapplyOrphan(*orphan, *same);
        } else {
          return fail(app, fmt::format("orphan-reapply N [selected], not `{}`", target));
        }
      } else if (cmd == "copy-file") {
        std::istringstream files(arg);
        std::string src, dst;
        if (!(files >> src >> dst)) return fail(app, "copy-file needs SRC DST");
        // As an exporter writes: the whole file under another name, then renamed over the old.
        const std::filesystem::path tmp = dst + ".part";
        std::error_code ec;
        std::filesystem::copy_file(src, tmp, std::filesystem::copy_options::overwrite_existing, ec);
        if (!ec) std::filesystem::rename(tmp, dst, ec);
        if (ec) return fail(app, fmt::format("cannot copy {} to {}: {}", src, dst, ec.message()));
        reloadsAtCopy_ = app.sceneReloads();
        cameraAtCopy_ = app.cameraView().position;
      } else if (cmd == "expect-reload") {
        reloadWaiting_ = true;
        reloadWaitStart_ = std::chrono::steady_clock::now();
        return;
      } else if (cmd == "save-image") {
        app.saveImage(arg);
      } else if (cmd == "append-line") {
        const auto space = arg.find(' ');
        if (space == std::string::npos) return fail(app, "append-line needs FILE TEXT");
        std::ofstream out(arg.substr(0, space), std::ios::app);
        out << "\n" << arg.substr(space + 1) << "\n";
        out.close();
        if (out.fail()) return fail(app, fmt::format("cannot append to {}", arg.substr(0, space)));
      } else if (cmd == "expect-shader-error") {
        if (!app.shaderReloader()) return fail(app, "no hot shader reload (shader sources not found)");
        waitShaderError_ = arg;
        shaderErrorFrames_ = 0;
        return;
      } else if (cmd == "open-capture") {
        app.session().openCapture(arg);
        app.showBuffers(true);
        app.pinPreview("");
      } else if (cmd == "close-capture") {
        app.session().closeCapture();
      } else if (cmd == "renderdoc-capture") {
        app.requestRenderDocCapture();
      } else if (cmd == "buffers") {
        app.showBuffers(arg == "on");
      } else if (cmd == "view") {
        app.pinPreview(arg == "final" ? "" : arg);
        app.viewer().refresh = true;
      } else if (cmd == "view-channel") {
        static const char* names[] = {"rgb", "r", "g", "b", "a", "luminance"};
        auto it = std::find(std::begin(names), std::end(names), arg);
        if (it == std::end(names)) return fail(app, fmt::format("unknown channel `{}`", arg));
        app.viewer().channel = uint32_t(it - std::begin(names));
        app.viewer().autoFitPending = true;
      } else if (cmd == "view-meaning") {
        if (arg != "on" && arg != "off") return fail(app, "view-meaning on|off");
        app.viewer().meaning = arg == "on";
        app.viewer().autoFitPending = true;
      } else if (cmd == "expect-meaning") {
        std::string decoder;
        for (const auto& r : app.session().resources())
          if (r.name == app.viewer().resource) decoder = r.desc.decoder;
        const auto m = shownMeaning(app.viewer(), decoder);
        const std::string shown = m ? m->quantity : "stored values";
        if (shown.find(arg) == std::string::npos)
          return fail(app, fmt::format("expected `{}` to show {}, but it shows {}", app.viewer().resource, arg, shown));
        if (m && m->fitted && app.viewer().autoFitPending)
          return fail(app, fmt::format("`{}`: the {} range is not fitted yet", app.viewer().resource, shown));
        fmt::print("script: `{}` shows {}{}\n", app.viewer().resource, shown,
                   m && m->fitted ? fmt::format(" over {:.4g} .. {:.4g} {}", app.viewer().rangeMin, app.viewer().rangeMax, m->unit)
                                  : std::string());
      } else if (cmd == "view-false-colour") {
        app.viewer().falseColour = arg == "on";
      } else if (cmd == "view-zoom") {
        float z, u, v;
        if (std::sscanf(arg.c_str(), "%f %f %f", &z, &u, &v) != 3) return fail(app, "view-zoom needs Z U V");
        app.viewer().zoom = z, app.viewer().centre = glm::vec2(u, v);
      } else if (cmd == "view-slice") {
        app.viewer().slice = uint32_t(std::stoul(arg));
      } else if (cmd == "expect-slice" || cmd == "expect-square-texels") {
        const graph::PhysicalInfo* info = nullptr;
        for (const auto& r : app.session().resources())
          if (r.name == app.viewer().resource) info = &r;
        if (!info) return fail(app, fmt::format("`{}` is not a resource of the frame", app.viewer().resource));
        const VkExtent3D e = info->desc.extent;
        if (cmd == "expect-slice") {
          const std::string shown = lighting::sliceMeaning(info->desc.decoder, e, app.viewer().slice);
          if (e.depth <= 1 || shown != arg)
            return fail(app, fmt::format("expected `{}`'s slice to read `{}`, but it reads `{}`", info->name, arg,
                                         e.depth > 1 ? shown : "nothing: it is 2D"));
          fmt::print("script: `{}` slice {}: {}\n", info->name, app.viewer().slice, shown);
        } else {
          // A texel's width and height on screen, from the window the viewer shows.
          const glm::vec4 w = viewerWindow(app.viewer());
          const glm::vec2 viewport = app.viewportSize();
          const float texelW = viewport.x / (w.z * float(e.width)), texelH = viewport.y / (w.w * float(e.height));
          if (!(std::abs(texelW / texelH - 1.0f) < 0.01f))
            return fail(app, fmt::format("`{}` ({}x{}) shows texels {:.3f} x {:.3f} px: not square", info->name, e.width,
                                         e.height, texelW, texelH));
          fmt::print("script: `{}` ({}x{}) shows square texels of {:.3f} px, window {:.3f} x {:.3f} of the image\n", info->name,
                     e.width, e.height, texelW, w.z, w.w);
        }
      } else if (cmd == "view-probe") {
        unsigned x, y;
        if (std::sscanf(arg.c_str(), "%u %u", &x, &y) != 2) return fail(app, "view-probe needs X Y");
        app.viewer().probe = glm::uvec3(x, y, app.viewer().slice);
      } else if (cmd == "keep-b") {
        app.viewer().keepCopy = true;
      } else if (cmd == "show-b") {
        app.viewer().showCopy = arg == "on";
      } else if (cmd == "expect-probe") {
        unsigned x, y;
        char text[256] = {};
        if (std::sscanf(arg.c_str(), "%u %u %255[^\n]", &x, &y, text) != 3) return fail(app, "expect-probe needs X Y TEXT");
        const ViewerState& v = app.viewer();
        std::string decoder;
        for (const auto& r : app.session().resources())
          if (r.name == v.resource) decoder = r.desc.decoder;
        // A volume is probed in the slice on view, as the viewport's own probe does.
        const auto lines = probeTexel(v, decoder, glm::uvec3(x, y, v.slice), app.session().decodingScene());
        if (!lines) return fail(app, fmt::format("`{}` was not read back", v.resource));
        std::string all;
        for (auto& [l, val] : lines->raw) all += l + " = " + val + "; ";
        for (auto& [l, val] : lines->decoded) all += l + ": " + val + "; ";
        bool found = false;  // TEXT may list alternatives: a|b
        std::istringstream alternatives{std::string(text)};
        for (std::string alt; std::getline(alternatives, alt, '|');) found |= !alt.empty() && all.find(alt) != std::string::npos;
        if (!found) return fail(app, fmt::format("probe of `{}` at {}, {} shows `{}`, not `{}`", v.resource, x, y, all, text));
        fmt::print("script: probe of `{}` at {}, {}: {}\n", v.resource, x, y, all);
      } else if (cmd == "expect-viewer-matches-capture") {
        const ViewerState& v = app.viewer();
        auto it = v.readbacks.find(v.resource);
        if (it == v.readbacks.end()) return fail(app, fmt::format("`{}` was not read back", v.resource));
        // The capture's file as its manifest describes it, decoded back to the frame's texels.
        const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(std::filesystem::path(arg) / "manifest.json"));
        nlohmann::json entry;
        for (const auto& r : manifest["resources"])
          if (r.value("name", "") == v.resource) entry = r;
        if (!entry.is_object() || !entry["file"].is_string()) return fail(app, fmt::format("`{}` is not in the capture", v.resource));
        session::CapturedImage img = session::readCaptureImage(std::filesystem::path(arg) / entry["file"].get<std::string>(),
                                                               entry.value("channelNames", std::vector<std::string>{}));
        const std::vector<float> mine = it->second.texels();
        const std::vector<float> theirs = img.integer ? img.values
            : session::decodeCaptureValues(entry.value("encoding", "linear"), entry.value("format", ""), img.values, img.channels,
                                           gpu::formatInfo(it->second.format).channels, manifest["camera"].value("znear", 0.0f));
        if (theirs.size() != mine.size()) return fail(app, fmt::format("{} values in the viewer, {} in the capture", mine.size(), theirs.size()));
        size_t differ = 0;
        for (size_t i = 0; i < mine.size(); ++i) differ += !(mine[i] == theirs[i] || (std::isnan(mine[i]) && std::isnan(theirs[i])));
        if (differ) return fail(app, fmt::format("{} of {} values differ between the viewer and the capture", differ, mine.size()));
        fmt::print("script: the viewer's `{}` equals the capture ({} values)\n", v.resource, mine.size());
      } else if (cmd == "compare") {
        std::istringstream sides(arg);
        std::string left, right;
        sides >> left >> right;
        if (left == "off") {
          app.setCompare(false);
        } else {
          if (right.empty()) return fail(app, "compare needs LEFT RIGHT (or off)");
          app.setCompare(true);
          app.compareView()->left = left, app.compareView()->right = right;
          app.session().setCompareView(app.compareView());  // an unknown side fails here, on its line
        }
      } else if (cmd == "compare-mode" || cmd == "compare-wipe") {
        if (!app.compareView()) return fail(app, "the viewport is not split (compare LEFT RIGHT first)");
        if (cmd == "compare-mode") app.compareView()->difference = arg == "difference";
        else app.compareView()->wipe = std::stof(arg);
      } else if (cmd == "expect-compare-errors") {
        session::LiveCompare* live = app.session().liveCompare();
        if (!live) return fail(app, "the viewport is not split");
        live->finishFlip();  // FLIP runs beside the frames: take the one under way
        std::string all;
        for (const auto& e : live->errors()) {
          if (e.path == app.session().referencePath()) continue;
          if (!e.relMse || !std::isfinite(*e.relMse) || !e.flip || !std::isfinite(*e.flip))
            return fail(app, fmt::format("no finite error for `{}` yet", e.path));
          all += fmt::format(" {} relMSE {:.4f} FLIP {:.4f} ({:.1f} ms);", e.path, *e.relMse, *e.flip, e.gpuMs);
        }
        const auto noise = live->referenceNoise();
        fmt::print("script: compare against the reference ({} spp, its noise relMSE {}, {}):{}\n", live->referenceSamples(),
                   noise ? fmt::format("{:.4f}", *noise) : std::string("not known yet"),
                   live->referenceTrusted() ? "ranks the paths" : "still converging", all);
      } else if (cmd == "camera-move") {
        double x, y, z;
        if (std::sscanf(arg.c_str(), "%lf %lf %lf", &x, &y, &z) != 3) return fail(app, "camera-move needs X Y Z (metres)");
        app.moveCamera({x, y, z});
        if (const session::LiveCompare* live = app.session().liveCompare())
          samplesAtMove_ = live->referenceSamples(), restartsAtMove_ = live->referenceRestarts();
      } else if (cmd == "expect-reference-restarted") {
        const session::LiveCompare* live = app.session().liveCompare();
        if (!live) return fail(app, "the viewport is not split");
        const std::string causes = lighting::describeParts(live->lastReferenceRestart());
        if (live->referenceRestarts() == restartsAtMove_)
          return fail(app, fmt::format("the reference did not restart: {} samples per pixel, {} before the move",
                                       live->referenceSamples(), samplesAtMove_));
        if ((", " + causes + ",").find(", " + arg + ",") == std::string::npos)
          return fail(app, fmt::format("the reference restarted for {}, not {}", causes, arg));
        if (live->referenceSamples() >= samplesAtMove_)
          return fail(app, fmt::format("the reference holds {} samples per pixel, not fewer than the {} before the move",
                                       live->referenceSamples(), samplesAtMove_));
        fmt::print("script: the reference restarted ({}): {} -> {} samples per pixel\n", causes, samplesAtMove_,
                   live->referenceSamples());
      } else if (cmd == "animation") {
        // play, pause, or a time in seconds (pauses there)
        if (arg == "play" || arg == "pause") {
          app.playing() = arg == "play";
        } else {
          app.playing() = false;
          app.session().setAnimationTime(std::stod(arg));
        }
      } else if (cmd == "set") {
        app.session().settings() = session::applySettingText(app.session().settings(), arg);
      } else if (cmd == "expect-setting") {
        std::istringstream a(arg);
        std::string name, want;
        a >> name >> want;
        const lighting::SettingInfo* s = lighting::findSetting(name);
        if (!s) return fail(app, fmt::format("unknown setting `{}`", name));
        const std::string have = lighting::formatSetting(*s, s->get(app.session().settings()));
        if (have != want) return fail(app, fmt::format("setting `{}` is {}, expected {}", name, have, want));
        fmt::print("setting {} = {}\n", name, have);
      } else if (cmd == "mouse-click") {
        float x, y;
        if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) return fail(app, "mouse-click needs X Y");
        app.input().click({x, y});
        return;
      } else if (cmd == "mouse-wheel") {
        float x, y, steps;
        if (std::sscanf(arg.c_str(), "%f %f %f", &x, &y, &steps) != 3) return fail(app, "mouse-wheel needs X Y STEPS");
        app.input().push({InputEvent::Kind::Move, {x, y}});
        app.input().push({InputEvent::Kind::Wheel, {}, 0, false, {0.0f, steps}});
        return;
      } else if (cmd == "click-ui" || cmd == "double-click-ui") {
        const auto item = trackedItem(arg);
        if (!item) return fail(app, fmt::format("no control `{}` on screen", arg));
        if (!item->visible) {
          // Drawn but scrolled out of its window: scroll to it first, as a person would, and
          // click once it is in view (a click at its old place would land on another control).
          if (++scrollFrames_ > 10) return fail(app, fmt::format("control `{}` stays out of view", arg));
          scrollToItem(arg);
          --next_;  // this line again next frame
          return;
        }
        if (item->covered) {
          // Under another window: bring its own to the front first, as a person would (a
          // click where it is drawn would land on the window over it).
          if (++scrollFrames_ > 10) return fail(app, fmt::format("control `{}` stays covered by another window", arg));
          raiseItemWindow(arg);
          --next_;
          return;
        }
        scrollFrames_ = 0;
        const glm::vec2 centre = 0.5f * (item->min + item->max);
        app.input().click(centre);
        if (cmd == "double-click-ui") app.input().click(centre);
        return;
      } else if (cmd == "key") {
        // [ctrl+][shift+]NAME: pressed and released within one frame, as a quick tap.
        std::string name = arg;
        std::vector<int> modifiers;
        for (auto [prefix, code] : {std::pair{"ctrl+", GLFW_KEY_LEFT_CONTROL}, std::pair{"shift+", GLFW_KEY_LEFT_SHIFT}})
          if (name.rfind(prefix, 0) == 0) modifiers.push_back(code), name = name.substr(std::strlen(prefix));
        const auto code = keyCode(name);
        if (!code) return fail(app, fmt::format("unknown key `{}`", name));
        for (int m : modifiers) app.input().push({InputEvent::Kind::Key, {}, m, true});
        app.input().push({InputEvent::Kind::Key, {}, *code, true});
        app.input().push({InputEvent::Kind::Key, {}, *code, false});
        for (int m : modifiers) app.input().push({InputEvent::Kind::Key, {}, m, false});
        return;
      } else if (cmd == "type") {
        for (unsigned char c : arg) app.input().push({InputEvent::Kind::Char, {}, int(c)});
        return;
      } else if (cmd == "expect-compare-mode") {
        if (!app.compareView()) return fail(app, "the viewport is not split");
        const std::string mode = app.compareView()->difference ? "difference" : "wipe";
        if (mode != arg) return fail(app, fmt::format("the compare view shows `{}`, not `{}`", mode, arg));
        fmt::print("script: the compare view shows `{}`\n", mode);
      } else if (cmd == "expect-viewing") {
        const std::string shown = app.pinnedPreview().empty() ? "final" : app.pinnedPreview();
        if (shown != arg) return fail(app, fmt::format("the viewport shows `{}`, not `{}`", shown, arg));
        fmt::print("script: the viewport shows `{}`\n", shown);
      } else if (cmd == "expect-notice") {
        const auto& notices = app.notices();
        auto it = std::find_if(notices.rbegin(), notices.rend(), [&](auto& n) { return n.text.find(arg) != std::string::npos; });
        if (it == notices.rend()) return fail(app, fmt::format("no message containing `{}`", arg));
        fmt::print("script: message: {}\n", it->text);
      } else if (cmd == "expect-labels-fit") {
        const auto& clipped = clippedLabels();
        if (!clipped.empty()) return fail(app, fmt::format("{} label(s) cut off, first: {}", clipped.size(), clipped.front()));
        fmt::print("script: every label fits\n");
      } else if (cmd == "quit") {
        app.requestQuit();
        return;
      } else if (std::string failure; runLightScriptCommand(app, cmd, arg, failure)) {
        if (!failure.empty()) return fail(app, failure);
      } else {
        return fail(app, fmt::format("unknown command `{}`", cmd));
      }
    } catch (const std::exception& e) {
      return fail(app, e.what());
    }
    if (waitLoaded_) return;
    return;  // one action per frame, as a person would
  }
}

}  // namespace tl::editor
