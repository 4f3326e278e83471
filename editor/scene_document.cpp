// The scene as an artist's document: one way it opens (whatever asked for it), one way it closes
// (everything that worked for it stops first), the work done on it that is not saved yet (asked
// about before it would go, shown in the window's title, written to a recovery file every little
// while), and File > Save.
#include "editor_app.h"

#include "session/captured_frame.h"
#include "session/settings_json.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace tl::editor {
namespace {

// The render settings an artist edits (the image size follows the viewport and is not one).
bool sameRenderSettings(const lighting::RenderSettings& a, const lighting::RenderSettings& b) {
  for (const lighting::SettingInfo& s : lighting::settingsSchema())
    if (!(s.flags & lighting::kSettingNoPanel) && s.get(a) != s.get(b)) return false;
  return true;
}

nlohmann::json panelSettingsJson(const lighting::RenderSettings& settings) {
  nlohmann::json j = session::settingsJson(settings);
  for (const lighting::SettingInfo& s : lighting::settingsSchema())
    if (s.flags & lighting::kSettingNoPanel) j.erase(std::string(s.name));
  return j;
}

std::string joinList(const std::vector<std::string>& items) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return text;
}

}  // namespace

std::string EditorApp::UnsavedWork::describe() const {
  std::vector<std::string> parts;
  if (lighting) parts.push_back("the lighting");
  if (settings) parts.push_back("the render settings");
  if (albedo) parts.push_back("the albedo overrides");
  return joinList(parts);
}

EditorApp::UnsavedWork EditorApp::unsavedWork() const {
  UnsavedWork w;
  if (!session_ || !session_->hasScene()) return w;
  w.lighting = !session::sameLighting(session_->lighting(), savedLighting_);
  w.settings = !sameRenderSettings(session_->settings(), savedRenderSettings_);
  w.albedo = session_->albedo().unsaved();
  return w;
}

// --- opening --------------------------------------------------------------------------------

void EditorApp::openScene(const std::filesystem::path& file, std::optional<std::filesystem::path> lighting) {
  if (load_.valid()) {
    notify(fmt::format("{} is still loading: open {} when it is done (or cancel it)",
                       loadingRequest_ ? loadingRequest_->file.filename().string() : "a scene", file.filename().string()));
    return;
  }
  if (question_) return;  // one question at a time; it is on screen
  UnsavedQuestion q;
  q.opening = std::make_pair(file, std::move(lighting));
  const UnsavedWork work = unsavedWork();
  if (!work.any()) return proceed(q);
  q.text = fmt::format("{} has unsaved work: {}.\nSave it before opening {}?", session_->scene().path.filename().string(),
                       work.describe(), file.filename().string());
  question_ = std::move(q);
}

void EditorApp::askToQuit() {
  if (question_) return;
  UnsavedQuestion q;
  q.quitting = true;
  const UnsavedWork work = unsavedWork();
  if (!work.any()) return proceed(q);
  q.text = fmt::format("{} has unsaved work: {}.\nSave it before quitting?", session_->scene().path.filename().string(),
                       work.describe());
  question_ = std::move(q);
}

void EditorApp::answer(Answer a) {
  if (!question_) return;
  const UnsavedQuestion q = std::move(*question_);
  question_.reset();
  if (a == Answer::Cancel) {
    notify(q.quitting ? "not quitting: the work stays open" : "not opened: the work stays open");
    return;
  }
  if (a == Answer::Save && !saveWork()) return;  // the error is on screen; nothing closes
  if (a == Answer::Discard) {
    notify(fmt::format("discarded the unsaved work on {}", session_->scene().path.filename().string()));
    // A discarded settings edit does not follow into the next scene.
    const uint32_t w = session_->settings().width, h = session_->settings().height;
    session_->settings() = savedRenderSettings_;
    session_->setSize(w, h);
  }
  proceed(q);
}

// The work on the scene is saved or discarded now (or there was none): its recovery file goes,
// unless the recovery it offered is still unanswered.
void EditorApp::proceed(const UnsavedQuestion& q) {
  if (session_->hasScene() && !recoveryOffer_) session::removeRecovery(recoveryPath());
  autosaved_.clear();
  if (q.quitting) {
    quit_ = true;
    return;
  }
  beginOpen({q.opening->first, q.opening->second});
}

void EditorApp::beginOpen(OpenRequest request) {
  loadingRequest_ = request;
  load_ = std::async(std::launch::async, [file = request.file] { return session::Session::parseScene(file); });
}

void EditorApp::cancelLoad() {
  // Parsing cannot be interrupted: it goes on owning only its own data, and its result is
  // dropped when it arrives (quitting waits for it, bounded).
  if (!load_.valid()) return;
  keptAcrossReload_.reset();
  loadingRequest_.reset();
  abandonedLoads_.push_back(std::move(load_));
  load_ = {};
}

void EditorApp::finishLoad() {
  const OpenRequest request = loadingRequest_.value_or(OpenRequest{});
  loadingRequest_.reset();
  std::unique_ptr<scene::Scene> loaded;
  try {
    loaded = load_.get();
  } catch (const std::exception& e) {
    load_ = {};
    keptAcrossReload_.reset();
    watchScene();  // a broken export is not retried until the file changes again
    showError(e.what());
    return;
  }
  load_ = {};
  const bool reload = keptAcrossReload_.has_value();
  stopSceneWork(reload ? "the reload" : fmt::format("opening {}", request.file.filename().string()), false);
  try {
    session_->installScene(std::move(loaded));
    settleOpenedScene(request);
  } catch (const std::exception& e) {
    keptAcrossReload_.reset();
    watchScene();
    showError(e.what());
  }
}

// The steps every way of opening shares, once the scene is installed.
void EditorApp::settleOpenedScene(const OpenRequest& request) {
  const bool reload = keptAcrossReload_.has_value();
  openedWith_ = request;
  const session::OpeningLighting opened = session::openingLighting(session_->scene(), request.lighting, true);
  session_->setLighting(opened.lighting);
  if (!reload) {
    camera_.reset(session_->view(), glm::length(session_->scene().bounds.size()));
    selected_.reset();
    selectedLight_.reset();
    gizmoDrag_.reset();
    preview_.clear();
    announceScene(opened);
    // The render settings saved with this scene (File > Save), over the ones in use.
    const std::string key = sceneKey();
    if (settings_.sceneSettings.contains(key)) {
      try {
        const uint32_t w = session_->settings().width, h = session_->settings().height;
        session_->settings() = session::applySettingsJson(session_->settings(), settings_.sceneSettings[key]);
        session_->setSize(w, h);
        notify(fmt::format("render settings saved with {}", session_->scene().path.filename().string()));
      } catch (const std::exception& e) {
        showError(fmt::format("the render settings saved with this scene are not applied: {}", e.what()));
      }
    }
    savedRenderSettings_ = session_->settings();
  }
  savedLighting_ = session_->lighting();
  watchScene();
  settings_.addRecent(std::filesystem::absolute(session_->scene().path).string());
  saveSettingsIfChanged();
  reopenAlbedoDatabase();
  // After the database: attaching one drops unsaved edits, which a reload puts back.
  if (reload) restoreAfterReload();
  history_.reset(session_->settings(), session_->lighting());
  updateWindowTitle();
  if (!reload) offerRecovery();
}

void EditorApp::announceScene(const session::OpeningLighting& opened) {
  const scene::Scene& s = session_->scene();
  showScenePanel_ = !s.warnings.empty();
  sceneReport_ = scene::sceneReport(s);
  if (!s.warnings.empty())
    notify(fmt::format("{} import warning{}: View > Scene", s.warnings.size(), s.warnings.size() == 1 ? "" : "s"));
  if (opened.defaultSun) {
    const session::Lighting& l = opened.lighting;
    const glm::dvec3 toSun = -glm::normalize(l.sunDirection);
    notify(fmt::format("no light in the file: a default sun of {:.0f} W/m2 at {:.0f} deg elevation and the sky (Lighting panel)",
                       l.sunIrradiance.r, glm::degrees(std::asin(std::clamp(toSun.y, -1.0, 1.0)))));
  }
  if (opened.readFrom) notify(fmt::format("lighting from {}", opened.readFrom->filename().string()));
  if (!opened.error.empty()) showError(opened.error);
}

// --- closing: the work for the scene stops --------------------------------------------------

bool EditorApp::waitBounded(const std::string& what, const std::function<bool()>& done, double seconds) {
  const auto start = std::chrono::steady_clock::now();
  bool said = false;
  while (!done()) {
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (waited > seconds) return false;
    if (!said && waited > 2.0) {
      fmt::print("waiting for {} to stop (at most {:.0f} s)\n", what, seconds);
      std::fflush(stdout);
      said = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

void EditorApp::stopSceneWork(const std::string& why, bool quitting) {
  lastStopped_.clear();
  const auto start = std::chrono::steady_clock::now();
  // A job that does not stop within the bound: quitting goes without it (the unsaved work is in
  // the recovery file), a scene change waits on, having said so.
  const auto overdue = [&](const std::string& what) {
    const std::string text = fmt::format("{} did not stop within {:.0f} s", what, kStopSeconds);
    if (quitting) {
      try {
        const session::RecoveredWork w = unsavedWorkRecord();
        if (!w.empty()) session::writeRecovery(recoveryPath(), w);
      } catch (const std::exception&) {
      }
      fmt::print(stderr, "twinlight: error: {}: quitting without waiting for it (unsaved work is in the recovery folder)\n", text);
      std::fflush(nullptr);
      std::_Exit(1);
    }
    showError(text + ": the scene change waits for it");
  };
  if (bake_) {
    // Stepped on this thread between frames: it stands between two batches, each committed.
    bake_->cancel();
    const albedo::BakeProgress& p = bake_->progress();
    lastStopped_.push_back(fmt::format("the albedo bake ({} of {} keys baked, kept in the database: Bake resumes)",
                                       p.baked, p.total));
    lastBakeSummary_ = fmt::format("cancelled for {}: baked {}, skipped {}, failed {} of {} keys", why, p.baked, p.skipped,
                                   p.failed, p.total);
    bake_.reset();
    session_->albedo().reload();
  }
  pollTune();  // a tune that has just ended hands over its presets first
  if (tune_ && tune_->running()) {
    // A child process: SIGTERM, then the bound. What it measured stays in its folder.
    if (!tune_->stop(kStopSeconds)) overdue("the tune");
    lastStopped_.push_back(fmt::format("the tune (its measurements are kept in {}: the same request resumes)",
                                       tune_->request().out.string()));
    lastTuneSummary_ = "stopped for " + why;
  }
  tune_.reset();
  if (session::LiveCompare* live = session_->liveCompare(); live && live->measuring()) {
    if (!waitBounded("the compare's FLIP measurement", [&] { return !live->measuring(); }, kStopSeconds))
      overdue("the compare's FLIP measurement");
    live->finishFlip();
    lastStopped_.push_back("the compare's FLIP measurement under way");
  }
  if (!inFlight_.empty() || session_->frameInFlight()) {
    const auto framesStart = std::chrono::steady_clock::now();
    const size_t frames = std::max<size_t>(inFlight_.size(), session_->framesInFlightNow());
    const std::string what = fmt::format("the {} path's frame{} under way", session_->path(), frames == 1 ? "" : "s");
    while (!inFlight_.empty()) {
      if (!waitBounded(what, [&] { return session_->frameDone(); }, kStopSeconds)) overdue(what);
      collectOneEngineFrame();
    }
    if (session_->frameInFlight()) {
      if (!waitBounded(what, [&] { return session_->frameDone(); }, kStopSeconds)) overdue(what);
      session_->finishFrame();
    }
    // Said when it was a wait a person notices (a reference frame on a slow device), not for
    // every ordinary frame finishing.
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - framesStart).count();
    if (waited > kNoticedSeconds)
      lastStopped_.push_back(fmt::format("{} frame{} of the {} path under way", frames, frames == 1 ? "" : "s", session_->path()));
  }
  if (quitting) {
    if (load_.valid()) cancelLoad();
    for (auto& f : abandonedLoads_)
      if (!waitBounded("a scene still being read", [&] { return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready; },
                       kStopSeconds))
        overdue("a scene still being read");
    if (!abandonedLoads_.empty()) lastStopped_.push_back("the reading of a cancelled scene");
    abandonedLoads_.clear();
  }
  gizmoDrag_.reset();
  sceneWatcher_.watch({}, glfwGetTime());
  if (lastStopped_.empty()) return;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string text = fmt::format("stopped {} for {} in {:.2f} s", joinList(lastStopped_), why, seconds);
  fmt::print("{}\n", text);
  notify(text);
}

// --- saving ---------------------------------------------------------------------------------

bool EditorApp::saveAlbedoEdits() {
  auto& lib = session_->albedo();
  if (!lib.unsaved()) return true;
  if (!lib.database()) {
    // Edits made before any database was open: the scene's own database is made for them (the
    // edits carried over).
    attachAlbedoDatabase(defaultAlbedoDatabase());
    notify(fmt::format("made the albedo database {} for the overrides", defaultAlbedoDatabase().string()));
  }
  lib.save();
  return true;
}

std::vector<session::RecoveredOverride> EditorApp::unsavedOverrides() const {
  std::vector<session::RecoveredOverride> edits;
  const auto& lib = session_->albedo();
  if (!lib.unsaved()) return edits;
  const std::map<albedo::AlbedoKey, albedo::OverrideEntry> stored =
      lib.database() ? lib.database()->overrides() : std::map<albedo::AlbedoKey, albedo::OverrideEntry>{};
  for (const auto& e : lib.entries()) {
    const auto it = stored.find(e.combination.key);
    const std::optional<glm::vec3> before = it == stored.end() ? std::nullopt : std::optional<glm::vec3>(it->second.rgb);
    if (e.override != before) edits.push_back({e.combination.key, e.override, e.combination.label});
  }
  for (const auto& o : lib.orphans())
    if (o.removed ? o.inDatabase : !o.inDatabase)
      edits.push_back({o.key, o.removed ? std::nullopt : std::optional<glm::vec3>(o.rgb), o.label});
  return edits;
}

void EditorApp::applyOverrides(const std::vector<session::RecoveredOverride>& edits) {
  auto& lib = session_->albedo();
  for (const auto& o : edits) {
    bool found = false;
    for (uint32_t c = 0; c < lib.entries().size(); ++c) {
      if (lib.entries()[c].combination.key != o.key) continue;
      found = true;
      if (lib.entries()[c].override == o.rgb) continue;
      if (o.rgb) lib.setOverride(c, *o.rgb);
      else lib.clearOverride(c);
    }
    if (!found && o.rgb) lib.keepOrphan(o.key, *o.rgb, o.label);
  }
}

bool EditorApp::saveWork() {
  if (!session_->hasScene()) return true;
  const UnsavedWork work = unsavedWork();
  std::vector<std::string> saved;
  bool ok = true;
  if (work.lighting) {
    if (saveLighting().empty()) ok = false;  // the error is shown
    else saved.push_back("the lighting");
  }
  if (work.settings) {
    settings_.sceneSettings[sceneKey()] = panelSettingsJson(session_->settings());
    saveSettingsIfChanged();
    savedRenderSettings_ = session_->settings();
    saved.push_back("the render settings");
  }
  if (work.albedo) {
    try {
      saveAlbedoEdits();
      saved.push_back("the albedo overrides");
    } catch (const std::exception& e) {
      showError(fmt::format("the albedo overrides were not saved: {}", e.what()));
      ok = false;
    }
  }
  if (ok) {
    session::removeRecovery(recoveryPath());
    autosaved_.clear();
  }
  if (!saved.empty()) notify(fmt::format("saved {} of {}", joinList(saved), session_->scene().path.filename().string()));
  updateWindowTitle();
  return ok;
}

void EditorApp::updateWindowTitle() {
  std::string title = "Twinlight";
  if (session_->hasCapture()) title = fmt::format("{} - Twinlight", session_->capture()->dir().filename().string());
  else if (session_->hasScene())
    title = fmt::format("{}{} - Twinlight", session_->scene().path.filename().string(), unsavedWork().any() ? "*" : "");
  if (title == windowTitle_) return;
  windowTitle_ = title;
  if (window_) glfwSetWindowTitle(window_, title.c_str());
}

void EditorApp::resizeWindow(int width, int height) {
  if (window_) glfwSetWindowSize(window_, width, height);
}

// --- the recovery file ----------------------------------------------------------------------

std::filesystem::path EditorApp::recoveryPath() const {
  return session::recoveryFile(configDirectory() / "recovery", session_->scene().path);
}

session::RecoveredWork EditorApp::unsavedWorkRecord() const {
  session::RecoveredWork w;
  if (!session_->hasScene()) return w;
  w.scene = session_->scene().path;
  if (!session::sameLighting(session_->lighting(), savedLighting_)) w.lighting = session_->lighting();
  if (!sameRenderSettings(session_->settings(), savedRenderSettings_)) w.settings = panelSettingsJson(session_->settings());
  w.overrides = unsavedOverrides();
  return w;
}

void EditorApp::autosave(double now) {
  if (!session_->hasScene() || load_.valid() || recoveryOffer_ || question_) return;
  if (now - lastAutosave_ < double(settings_.autosaveSeconds)) return;
  lastAutosave_ = now;
  const session::RecoveredWork w = unsavedWorkRecord();
  const std::filesystem::path file = recoveryPath();
  if (w.empty()) {
    if (!autosaved_.empty()) session::removeRecovery(file), autosaved_.clear();
    return;
  }
  // Written again only when the work changed since.
  std::string record = w.lighting ? session::lightingJson(*w.lighting, {}) : std::string();
  record += w.settings ? w.settings->dump() : std::string();
  for (const auto& o : w.overrides)
    record += fmt::format("{}:{}", albedo::keyToHex(o.key), o.rgb ? fmt::format("{} {} {}", o.rgb->r, o.rgb->g, o.rgb->b) : "-");
  if (record == autosaved_) return;
  try {
    session::writeRecovery(file, w);
    autosaved_ = std::move(record);
    fmt::print("autosaved the unsaved work ({}) to {}\n", unsavedWork().describe(), file.string());
    std::fflush(stdout);
  } catch (const std::exception& e) {
    spdlog::warn("unsaved work not autosaved: {}", e.what());
  }
}

void EditorApp::offerRecovery() {
  recoveryOffer_.reset();
  const std::filesystem::path file = recoveryPath();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return;
  try {
    const session::RecoveredWork w = session::readRecovery(file);
    std::vector<std::string> parts;
    if (w.lighting) parts.push_back("the lighting");
    if (w.settings) parts.push_back("the render settings");
    if (!w.overrides.empty()) parts.push_back(fmt::format("{} albedo override{}", w.overrides.size(), w.overrides.size() == 1 ? "" : "s"));
    recoveryOffer_ = RecoveryOffer{file, fmt::format("{} had unsaved work when Twinlight last stopped without closing\n"
                                                     "(written {}): {}.\nRecover it?",
                                                     session_->scene().path.filename().string(), w.savedAt, joinList(parts))};
  } catch (const std::exception& e) {
    // Kept under another name, not offered again: nothing an artist did is deleted unasked.
    std::filesystem::path kept = file;
    kept += ".unreadable";
    std::filesystem::rename(file, kept, ec);
    showError(fmt::format("the recovery file of this scene cannot be read ({}); it is kept as {}", e.what(), kept.string()));
  }
}

void EditorApp::answerRecovery(bool recover) {
  if (!recoveryOffer_) return;
  const RecoveryOffer offer = std::move(*recoveryOffer_);
  recoveryOffer_.reset();
  if (!recover) {
    session::removeRecovery(offer.file);
    notify("discarded the recovered work");
    return;
  }
  try {
    const session::RecoveredWork w = session::readRecovery(offer.file);
    // Applied as edits: unsaved until File > Save, and Ctrl+Z goes back to the file as saved.
    if (w.lighting) session_->setLighting(*w.lighting);
    if (w.settings) {
      const uint32_t width = session_->settings().width, height = session_->settings().height;
      session_->settings() = session::applySettingsJson(session_->settings(), *w.settings);
      session_->setSize(width, height);
    }
    applyOverrides(w.overrides);
    // The file stays until the work is saved or discarded: a second crash loses nothing either.
    autosaved_.clear();
    notify(fmt::format("recovered the unsaved work written {} (File > Save keeps it)", w.savedAt));
  } catch (const std::exception& e) {
    showError(fmt::format("the work could not be recovered: {}", e.what()));
  }
}

}  // namespace tl::editor
