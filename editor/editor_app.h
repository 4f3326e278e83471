// The editor: a GLFW window with Dear ImGui over the engine's session. The interface never
// waits for the engine: the session renders on a device of its own, one frame at a time,
// submitted by the UI thread and collected when the GPU is done, while the UI goes on at its
// own rate; the latest finished frame (its display image, read back) is blitted into the
// swapchain under a transparent viewport panel, with its age, and the UI drawn over it.
// Nor does it wait for the window: the window is drawn only when what it shows changed
// (window_redraw.h), on a thread of its own (window_presenter.h).
#pragma once

#include "buffer_viewer.h"
#include "frame_profile.h"
#include "camera_controller.h"
#include "input_queue.h"
#include "light_gizmo.h"
#include "panel_layout.h"
#include "scene_watcher.h"
#include "settings.h"
#include "tune_job.h"
#include "window_presenter.h"
#include "window_redraw.h"

#include "gpu/descriptor_pool.h"
#include "gpu/shader_reload.h"
#include "session/edit_history.h"
#include "session/lighting_file.h"
#include "session/recovery.h"
#include "session/session.h"

#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>

struct GLFWwindow;

namespace tl::editor {

class Script;

class EditorApp {
 public:
  // `materials`: the material override mode the session starts with (`--materials`).
  // `lighting`: a lighting file (`--lighting`) for the first scene, in place of its sidecar.
  EditorApp(std::optional<std::filesystem::path> scene, std::optional<std::filesystem::path> script,
            lighting::MaterialMode materials = lighting::MaterialMode::Authored,
            std::optional<std::filesystem::path> lighting = std::nullopt);
  ~EditorApp();
  int run();  // exit code

  // --- used by the panels and the script runner -------------------------------------
  session::Session& session() { return *session_; }
  Settings& settings() { return settings_; }
  // Opens a scene (scene_document.cpp). Every way a scene opens goes through here and through the
  // same steps: the one named at start-up or on the command line, File > Open and Open recent, a
  // file dropped on the window, a script's `open`. `lighting` (`--lighting`) is applied to this
  // scene in place of its sidecar, and to no other. With unsaved work the editor asks first
  // (save, discard, cancel); the file is then read in the background, and everything that
  // worked for the scene before stops before the new one is installed.
  void openScene(const std::filesystem::path& file, std::optional<std::filesystem::path> lighting = std::nullopt);
  // A capture folder (manifest.json + EXRs) in the viewer, without its scene.
  void openCapture(const std::filesystem::path& dir);
  bool loading() const { return load_.valid(); }
  // Loads the scene's file again, keeping the camera, the selection (by instance name), the
  // albedo overrides of unchanged mesh + material combinations, edited lighting and the
  // animation time. Called when the file changes on disk (scene_reload.cpp).
  void reloadScene();
  // Unsaved work (scene_document.cpp): the lighting, the render settings (a preset applied is a
  // settings edit) and the albedo overrides as they differ from what was opened or last saved.
  struct UnsavedWork {
    bool lighting = false, settings = false, albedo = false;
    bool any() const { return lighting || settings || albedo; }
    std::string describe() const;  // "the lighting and the albedo overrides"
  };
  UnsavedWork unsavedWork() const;
  // File > Save (Ctrl+S): the lights into the glTF and everything into its lighting sidecar, the
  // overrides into the albedo database (the scene's default one when none is open), the render
  // settings as this scene's (reapplied when it opens). False, with the error shown, when
  // something could not be written (what could be is).
  bool saveWork();
  // The question asked before unsaved work would go (quitting, opening another scene); the
  // answer carries out what was asked, or nothing (cancel).
  enum class Answer { Save, Discard, Cancel };
  struct UnsavedQuestion {
    std::string text;
    bool quitting = false;
    std::optional<std::pair<std::filesystem::path, std::optional<std::filesystem::path>>> opening;  // scene, lighting
  };
  const std::optional<UnsavedQuestion>& unsavedQuestion() const { return question_; }
  void answer(Answer a);
  // A recovery file of the scene just opened: work an editor that did not close had not saved.
  struct RecoveryOffer {
    std::filesystem::path file;
    std::string text;
  };
  const std::optional<RecoveryOffer>& recoveryOffer() const { return recoveryOffer_; }
  void answerRecovery(bool recover);
  // "lamps.gltf* - Twinlight": the scene, marked while it holds unsaved work.
  const std::string& windowTitle() const { return windowTitle_; }
  // What the last scene change or quit stopped ("the albedo bake (12 of 40 keys baked, kept)").
  const std::vector<std::string>& lastStopped() const { return lastStopped_; }
  uint64_t sceneReloads() const { return sceneReloads_; }
  session::View cameraView() const { return camera_.view(); }
  // File > Save image: the last frame as .png (display) or .exr (linear radiance). Throws
  // SessionError naming the file when it cannot be written.
  void saveImage(const std::filesystem::path& file);
  std::filesystem::path defaultImagePath(const char* extension) const;
  void cancelLoad();
  void setPath(const std::string& name);
  // An instance or a light is selected, not both.
  void select(std::optional<uint32_t> instance) {
    selected_ = instance;
    if (instance) selectedLight_.reset();
  }
  void selectLight(std::optional<size_t> light) {
    selectedLight_ = light;
    if (light) selected_.reset(), lightsTabRequest_ = true;
  }
  // Whether the outliner should bring its Lights tab forward (once, after a light was selected elsewhere).
  bool takeLightsTabRequest() { return std::exchange(lightsTabRequest_, false); }
  std::optional<uint32_t> selected() const { return selected_; }
  void clickViewport(glm::vec2 windowPos);    // picks the instance under the cursor
  void requestScreenshot(const std::filesystem::path& file) { screenshotPath_ = file; }
  // A screenshot asked for and not yet written (the window's thread takes it).
  bool screenshotPending() const { return screenshotPath_ || (presenter_ && presenter_->screenshotPending()); }
  // Writes every buffer of the next engine frame into `dir` (EXR + manifest.json).
  void requestFrameCapture(const std::filesystem::path& dir) { frameCapturePath_ = dir; }
  // Quits at once: unsaved work is discarded (a script's `quit`, a failed script).
  void requestQuit() { quit_ = true; }
  // File > Quit, the window's close button: asks first when there is unsaved work.
  void askToQuit();
  // Throws SessionError with the reason when RenderDoc is not attached.
  void requestRenderDocCapture();
  std::filesystem::path defaultCaptureFolder() const;
  bool frameCapturePending() const { return frameCapturePath_ || captureInFlight_; }
  // Reads back the viewport image (display.ldr) of the next engine frame, for scripted checks.
  void requestViewportCapture() { captureRequested_ = true, capture_.clear(); }
  const std::vector<float>& viewportCapture() const { return capture_; }
  // Engine frames finished so far, and whether the engine has anything to render now.
  uint64_t engineFramesDone() const { return engineFramesDone_; }
  uint64_t engineFramesBegun() const { return engineFramesBegun_; }
  bool engineActive() const;
  // Frames per second of the interface and of the engine, over the last second or so, and
  // how old (seconds since its input was taken) the frame on screen is.
  double engineFps() const;
  double shownFrameAge() const;
  // The figures the panels show (rates, the frame's age, the loop's recent pass times),
  // refreshed a few times a second rather than every pass: a figure that changed every pass
  // would have the window drawn again every pass (window_redraw.h).
  struct ShownFigures {
    double uiFps = 0.0, presentedFps = 0.0, engineFps = 0.0, frameAgeMs = 0.0;
    std::vector<float> passMs;  // the loop's recent passes, oldest first
    double at = -1.0;           // glfwGetTime() when taken
  };
  const ShownFigures& shownFigures() const { return figures_; }
  InputQueue& input() { return input_; }
  // Undo and redo across the edit histories (render settings and lighting, albedo overrides):
  // the latest edit first, whichever it was; Ctrl+Z / Ctrl+Y. Each returns what it did ("" = nothing).
  std::string undo();
  std::string redo();
  session::EditHistory& editHistory() { return history_; }
  // Lights (the Lights panel, the viewport's icons and gizmo). Each edit is a lighting edit of
  // the session (undoable). New lights stand in front of the camera.
  std::optional<size_t> selectedLight() const { return selectedLight_; }
  void addLight(scene::LightType type);
  void duplicateSelectedLight();
  void deleteSelectedLight();
  // Hides every light but the selected one; when it already shows alone, shows them all.
  void soloSelectedLight();
  // File > Save lighting: the lights into the scene's glTF (KHR_lights_punctual) and everything
  // into SCENE.lighting.json beside it (session/lighting_file.h saveSceneLighting). Returns what
  // was written; errors go to the status bar.
  std::string saveLighting();
  void loadEnvironmentMap(const std::string& file);
  std::string& environmentField() { return environmentField_; }
  // The editor camera's view on the viewport panel, for the light overlay.
  ViewportProjection viewportProjection() const;
  // Whether the viewport shows the final image unzoomed, where the light overlay belongs.
  bool overlayShown() const;
  bool& lightOverlayOpen() { return showLightOverlay_; }
  GizmoHandle activeGizmoHandle() const { return gizmoDrag_ ? gizmoDrag_->handle : GizmoHandle::None; }
  // The last finished gizmo drag (scripts check that the light followed the mouse).
  struct FinishedGizmoDrag {
    GizmoDrag drag;
    glm::vec2 endMouse{0.0f};
    scene::Light end;
    ViewportProjection projection;
  };
  const std::optional<FinishedGizmoDrag>& lastGizmoDrag() const { return lastGizmoDrag_; }
  void focusSelection();
  // Moves the editor camera by metres along its right, up and forward axes.
  void moveCamera(const glm::dvec3& rightUpForward) { camera_.translate(rightUpForward); }
  void showError(const std::string& message) { error_ = message; }
  // A confirmation or note for the status bar (and the Messages list): what was written
  // where, what was done for you (a default light, a fallback to the final image).
  void notify(const std::string& text);
  struct Notice {
    std::string text;
    double time = 0.0;  // glfwGetTime()
  };
  const std::deque<Notice>& notices() const { return notices_; }
  // The latest notice if it is recent enough to show (a few seconds), else null.
  const Notice* recentNotice() const;
  void previewResource(const std::string& name) { preview_ = name; }  // while hovering a pass
  // Shows a resource in the viewport until changed ("" = the final image); its range is fitted.
  void pinPreview(const std::string& name) {
    if (name != viewer_.resource) viewer_.autoFitPending = true, viewer_.probe.reset(), viewer_.slice = 0;
    viewer_.resource = name;
  }
  ViewerState& viewer() { return viewer_; }
  void showBuffers(bool on) { showBuffers_ = on; }
  bool& buffersOpen() { return showBuffers_; }
  // The Compare panel: while compareView() holds a value the viewport is split between two
  // paths (applied to the session each frame; an unavailable side is refused with its reason).
  bool& compareOpen() { return showCompare_; }
  bool& scenePanelOpen() { return showScenePanel_; }  // opens itself for a scene with warnings
  // The loaded scene's report (scene::sceneReport), made once per scene for the Scene panel.
  const std::vector<std::string>& sceneReport() const { return sceneReport_; }
  // Morph animations advance with the wall clock while playing (on by default).
  bool& playing() { return playing_; }
  std::optional<session::CompareView>& compareView() { return compareView_; }
  void setCompare(bool on);
  // Hot shader reload: null where the shader sources are not around (an installed build).
  const gpu::ShaderReloader* shaderReloader() const { return reloader_.get(); }
  const std::string& shaderStatus() const { return shaderStatus_; }
  void showHelp(bool on) { showHelp_ = on; }
  // The albedo database: bakes run one batch per frame so the UI stays responsive.
  void openAlbedoDatabase(const std::filesystem::path& file);
  // A status-bar note that overrides lost their mesh + material (the Albedo panel lists them).
  void notifyOrphans();
  void startAlbedoBake(bool force);
  void cancelAlbedoBake() { if (bake_) bake_->cancel(); }
  const albedo::BakeJob* albedoBake() const { return bake_.get(); }
  std::string& albedoDbField() { return albedoDbField_; }
  // The database proposed for the scene: the one last opened for it, else
  // out/<file stem>-<hash of its absolute path>.albedo.db (two scene.gltf files differ).
  std::filesystem::path defaultAlbedoDatabase() const;
  const std::string& lastBakeSummary() const { return lastBakeSummary_; }
  // Lighting › Tune for this view (tune_view.cpp): `twinlight tune` on this scene, camera and
  // settings in a child process, one at a time; the scene's work like the bake (stopSceneWork
  // stops it). The request's scene, path, view, settings and folder are filled in here.
  void startTune(TuneRequest request);
  TuneJob* tuneJob() { return tune_.get(); }
  void stopTune();
  // What the last tune did ("3 presets: tuned-cornell-rt-1x-legacy, ..."), and their names.
  const std::string& lastTuneSummary() const { return lastTuneSummary_; }
  const std::vector<std::string>& lastTunePresets() const { return lastTunePresets_; }
  const std::string& pinnedPreview() const { return viewer_.resource; }
  void showBrowser(bool on) { showBrowser_ = on; }
  // Passes of the UI loop (each takes the input, runs the panels, starts and collects engine
  // frames): the interface's frame rate. A pass whose window would look as it does is not
  // drawn; framesPresented() counts the window frames presented, framesSuperseded() those
  // handed to the window's thread and replaced by a newer one before it got to them.
  uint64_t uiFrames() const { return uiFrames_; }
  uint64_t framesPresented() const { return presenter_ ? presenter_->presented() : 0; }
  uint64_t framesSuperseded() const { return presenter_ ? presenter_->superseded() : 0; }
  // Where the UI frames' wall time went since the start (`measure` prints the differences).
  const FrameProfile& frameProfile() const { return profile_; }
  double fps() const;            // UI loop passes per second, over the last 30
  const std::deque<double>& frameHistoryMs() const { return frameHistory_; }
  // Resizes the window as a person dragging its corner does (the layout and the engine's image follow).
  void resizeWindow(int width, int height);
  // Where the panels sit this frame (panel_layout.h): the tool panels beside the viewport.
  const PanelLayout& panelLayout() const { return layout_; }
  // Viewport panel rectangle in window pixels (valid after the first frame).
  glm::vec2 viewportMin() const { return viewportMin_; }
  glm::vec2 viewportSize() const { return viewportSize_; }

 private:
  void createWindow();
  void initImgui();
  void frame();
  void drawUi();
  void handleCameraInput(float seconds);
  void startEngineFrame();
  void collectEngineFrame();
  void collectOneEngineFrame();
  void presentIfChanged();
  void refreshShownFigures(double now);
  void finishLoad();
  // The scene opening (scene_document.cpp): what was asked for and the steps every way shares.
  struct OpenRequest {
    std::filesystem::path file;
    std::optional<std::filesystem::path> lighting;  // --lighting, for this scene only
  };
  void beginOpen(OpenRequest request);
  void settleOpenedScene(const OpenRequest& request);
  // Everything that works for the scene stops before it goes (another scene, a reload, quitting):
  // the albedo bake, the compare's measurement, the frames under way. Each stops within
  // kStopSeconds or the editor says which did not; `why` goes into the message.
  static constexpr double kStopSeconds = 20.0;
  static constexpr double kNoticedSeconds = 0.5;  // a wait shorter than this is not reported
  void stopSceneWork(const std::string& why, bool quitting);
  // Waits until `done` or `seconds` passed, saying what it waits for after a moment; false on timeout.
  bool waitBounded(const std::string& what, const std::function<bool()>& done, double seconds);
  void markSaved();            // what is open now is what is saved
  void updateWindowTitle();
  void autosave(double now);   // the recovery file, every settings_.autosaveSeconds while work is unsaved
  session::RecoveredWork unsavedWorkRecord() const;
  std::filesystem::path recoveryPath() const;
  void offerRecovery();
  bool saveAlbedoEdits();
  // The albedo edits not in the database (what differs from it), and those applied as edits.
  std::vector<session::RecoveredOverride> unsavedOverrides() const;
  void applyOverrides(const std::vector<session::RecoveredOverride>& edits);
  void proceed(const UnsavedQuestion& question);
  std::optional<OpenRequest> loadingRequest_;
  OpenRequest openedWith_;  // how the scene shown was opened (a reload opens it the same way)
  std::vector<std::future<std::unique_ptr<scene::Scene>>> abandonedLoads_;  // cancelled, still parsing
  session::Lighting savedLighting_;            // the lighting as opened or last saved
  lighting::RenderSettings savedRenderSettings_;  // the render settings as opened or last saved
  std::optional<UnsavedQuestion> question_;
  std::optional<RecoveryOffer> recoveryOffer_;
  std::string windowTitle_;
  std::vector<std::string> lastStopped_;
  double lastAutosave_ = 0.0;
  std::string autosaved_;  // the recovery record last written ("" = none)
  void applyBookmark(int slot, bool save);
  void saveSettingsIfChanged();
  void reopenAlbedoDatabase();
  void attachAlbedoDatabase(const std::filesystem::path& file);  // openAlbedoDatabase without notes
  std::string sceneKey() const;

  Settings settings_;
  session::EditHistory history_;  // render settings and lighting; reset with each scene
  nlohmann::json savedSettings_;  // what settings.json holds now
  GLFWwindow* window_ = nullptr;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  std::unique_ptr<gpu::Device> uiDevice_;  // the window's: swapchain, Dear ImGui, the viewport image
  std::unique_ptr<session::Session> session_;
  std::unique_ptr<WindowPresenter> presenter_;
  // The engine image last handed to the window (an equal one is not handed again) and a new
  // one waiting for the next window frame.
  std::vector<uint8_t> shownImage_;
  std::optional<graph::Readback> newImage_;
  bool imageShown_ = false;
  InputQueue input_;
  std::unique_ptr<gpu::DescriptorPool> imguiPool_;
  std::unique_ptr<Script> script_;
  CameraController camera_;
  std::future<std::unique_ptr<scene::Scene>> load_;
  std::optional<uint32_t> selected_;
  std::optional<glm::vec2> pendingClick_;
  std::optional<std::filesystem::path> screenshotPath_;
  std::string error_;
  std::string preview_;        // resource shown while a pass is hovered ("" = none)
  ViewerState viewer_;         // what is shown otherwise, and how (the Buffers panel)
  bool showBuffers_ = false;
  bool showCompare_ = false;
  bool showScenePanel_ = false;
  std::vector<std::string> sceneReport_;
  void announceScene(const session::OpeningLighting& opened);  // warnings and the lighting of a scene just opened
  bool playing_ = true;
  std::optional<session::CompareView> compareView_;
  bool draggingWipe_ = false;
  glm::vec2 viewportMin_{0.0f}, viewportSize_{0.0f};
  PanelLayout layout_;
  bool viewportHovered_ = false;
  bool showHelp_ = false, showBrowser_ = false;
  std::filesystem::path browserDir_;
  bool quit_ = false;
  bool captureRequested_ = false;
  std::vector<float> capture_;
  // What the engine frame in flight was asked for beyond the image, collected when it is done.
  struct FrameAsks {
    double begunAt = 0.0;          // glfwGetTime() when its input was taken
    bool viewerReads = false;      // the viewer's resource and companions
    bool keepCopy = false;         // the viewer's A/B copy
    bool snapshot = false;         // the viewport for a script
    std::optional<std::filesystem::path> capture;  // every buffer, into this folder
    std::string viewed;            // the viewer's resource when it began
  };
  // Oldest first: up to the session's frames in flight, collected in the order begun.
  std::deque<FrameAsks> inFlight_;
  uint32_t engineFrameLimit() const;
  bool renderDocPending_ = false;
  std::deque<Notice> notices_;
  bool captureInFlight_ = false;
  uint64_t engineFramesDone_ = 0, engineFramesBegun_ = 0;
  std::deque<double> engineFrameEnds_;  // glfwGetTime() of recent finished frames
  double shownBegunAt_ = -1.0;          // input time of the frame on screen
  std::vector<uint8_t> pickIds_;        // gbuffer.instanceId of the frame on screen
  VkExtent3D pickExtent_{};
  uint64_t uiFrames_ = 0;
  WindowRedraw redraw_;
  ShownFigures figures_;
  uint64_t presentedAtFigures_ = 0;  // framesPresented() when the figures were taken
  FrameProfile profile_;
  std::deque<double> frameHistory_;
  double lastTime_ = 0.0;
  double nextPassAt_ = 0.0;  // glfwGetTime() the next pass of the UI loop is due
  glm::vec2 lastMouse_{0.0f};
  glm::vec2 pressPos_{0.0f};
  bool dragged_ = false;
  std::optional<size_t> selectedLight_;
  std::optional<GizmoDrag> gizmoDrag_;
  std::optional<FinishedGizmoDrag> lastGizmoDrag_;
  bool overlayPress_ = false;  // the left button went down on a light icon or gizmo handle
  bool showLightOverlay_ = true;
  bool lightsTabRequest_ = false;
  bool interactionActive_ = false;   // a widget or handle was held last frame
  bool interactionChanged_ = false;  // and the hold has made an edit step already
  std::string environmentField_;
  bool handleLightOverlayInput(glm::vec2 mouse);  // true: the overlay took the mouse

  friend void drawPanels(EditorApp& app);
  friend class Script;
  std::optional<std::filesystem::path> frameCapturePath_;
  std::unique_ptr<albedo::BakeJob> bake_;
  std::unique_ptr<TuneJob> tune_;
  std::string lastTuneSummary_;
  std::vector<std::string> lastTunePresets_;
  void pollTune();  // every frame: when the tune has ended, its presets join the presets folder
  std::unique_ptr<gpu::ShaderReloader> reloader_;
  std::string shaderStatus_;
  void pollShaders();
  std::string albedoDbField_;     // the Albedo panel's database path
  // Reloading the scene when its file changes (scene_reload.cpp).
  struct KeptAcrossReload {
    std::string selected;  // instance name
    // The unsaved override edits, a cleared override too (else the database's would come back).
    std::vector<session::RecoveredOverride> overrides;
    std::optional<session::Lighting> lighting;  // when edited away from the scene's own
    double animationTime = 0.0;
  };
  SceneWatcher sceneWatcher_;
  std::optional<KeptAcrossReload> keptAcrossReload_;  // while a reload is loading
  uint64_t sceneReloads_ = 0;
  void watchScene();
  void restoreAfterReload();
  std::string lastBakeSummary_;
  void stepAlbedoBake();
};

}  // namespace tl::editor
