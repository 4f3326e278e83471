// Lighting › Tune for this view: the editor's side of a tune job (tune_job.h). The request
// takes this scene, camera, path and settings; its folder is named by what it asks, so asking
// again after a stop resumes it.
#include "editor_app.h"
#include "session/provenance.h"
#include "session/settings_json.h"
#include "settings_panel.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

namespace tl::editor {

namespace fs = std::filesystem;

namespace {

// FNV-1a of the request's arguments: the same request, the same folder (and its measurements).
uint64_t requestHash(const std::vector<std::string>& args) {
  uint64_t h = 1469598103934665603ull;
  for (const std::string& a : args)
    for (char c : a + '\n') h = (h ^ uint8_t(c)) * 1099511628211ull;
  return h;
}

}  // namespace

void EditorApp::startTune(TuneRequest request) {
  if (tune_ && tune_->running()) {
    showError("a tune is running already: stop it first");
    return;
  }
  if (!session_->hasScene()) {
    showError("Tune for this view: no scene is open");
    return;
  }
  request.scene = session_->scene().path;
  if (request.path.empty()) request.path = session_->path();
  request.view = cameraView();
  request.settings = session_->settings();
  if (request.out.empty()) {
    request.out = "pending";
    // The scene's content is in the key (a saved edit is another request, not a resume), and the
    // build (another build measures afresh: its folder's plan may have other fields).
    const uint64_t key = requestHash(tuneArguments(request)) ^
                         requestHash({session::settingsJson(request.settings).dump(),
                                      fmt::format("{:016x}", session_->scene().contentHash),
                                      session::twinlightJson().dump()});
    request.out = configDirectory() / "tune" / fmt::format("{}-{}-{:016x}", request.scene.stem().string(), request.path, key);
  }
  try {
    tune_ = TuneJob::start(request);
    lastTuneSummary_ = fmt::format("tuning {} for this view into {}", request.path, request.out.string());
    lastTunePresets_.clear();
    notify(lastTuneSummary_);
  } catch (const std::exception& e) {
    showError(e.what());
  }
}

void EditorApp::stopTune() {
  if (!tune_) return;
  if (tune_->running()) {
    tune_->stop(kStopSeconds);
    lastTuneSummary_ = fmt::format("stopped; its measurements are kept in {} (the same request resumes)",
                                   tune_->request().out.string());
    notify("tune " + lastTuneSummary_);
  }
  tune_.reset();
}

void EditorApp::pollTune() {
  if (!tune_ || tune_->running()) return;
  const int status = tune_->exitStatus().value_or(-1);
  const std::string scene = tune_->request().scene.stem().string();
  lastTunePresets_.clear();
  std::error_code ec;
  fs::create_directories(presetDirectory(), ec);
  for (const fs::path& file : tune_->presets()) {
    // preset-rt-1x-legacy.json -> tuned-cornell-rt-1x-legacy.json in the presets folder.
    const std::string name = "tuned-" + scene + "-" + file.stem().string().substr(std::string("preset-").size());
    fs::copy_file(file, presetDirectory() / (name + ".json"), fs::copy_options::overwrite_existing, ec);
    if (ec) {
      showError(fmt::format("tune: cannot copy {} into {}: {}", file.string(), presetDirectory().string(), ec.message()));
      continue;
    }
    lastTunePresets_.push_back(name);
  }
  if (status == 0) {
    lastTuneSummary_ = fmt::format("finished: {} preset(s) in Preset: {}", lastTunePresets_.size(),
                                   lastTunePresets_.empty() ? std::string("none") : fmt::format("{}", fmt::join(lastTunePresets_, ", ")));
    notify("tune " + lastTuneSummary_);
  } else {
    lastTuneSummary_ = fmt::format("ended with exit status {} ({} preset(s)): {} (log: {})", status, lastTunePresets_.size(),
                                   tune_->lastLine(), (tune_->request().out / "tune.log").string());
    showError("tune " + lastTuneSummary_);
  }
  tune_.reset();
}

}  // namespace tl::editor
