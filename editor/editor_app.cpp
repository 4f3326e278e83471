#include "editor_app.h"

#include "gpu/install_paths.h"
#include "gpu/renderdoc.h"
#include "session/capture.h"
#include "session/image_io.h"

#include "script.h"

#include <GLFW/glfw3.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/thread.h>
#include <cmath>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <thread>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace tl::editor {

void drawPanels(EditorApp& app);

namespace {

std::string imguiIniPath;  // ImGui keeps the pointer: it must outlive the context
std::vector<std::string> droppedFiles;
// The window was exposed (uncovered, restored): its pixels are the editor's to draw again.
bool windowExposed = true;

void onDrop(GLFWwindow*, int count, const char** paths) {
  for (int i = 0; i < count; ++i) droppedFiles.emplace_back(paths[i]);
}

void onRefresh(GLFWwindow*) { windowExposed = true; }

void checkVk(VkResult r) {
  if (r != VK_SUCCESS) throw gpu::Error(fmt::format("Dear ImGui's Vulkan backend: {}", gpu::resultName(r)));
}

}  // namespace

EditorApp::EditorApp(std::optional<std::filesystem::path> scene, std::optional<std::filesystem::path> script,
                     lighting::MaterialMode materials, std::optional<std::filesystem::path> lighting) {
  settings_ = loadSettings();
  savedSettings_ = toJson(settings_);
  browserDir_ = std::filesystem::current_path();
  createWindow();
  initImgui();
  if (script) script_ = std::make_unique<Script>(*script);
  // Edit a shader under shaders/ or a plugin's under plugins/ while the editor runs: it is
  // recompiled and swapped in. An installed program without the source tree has none to watch.
  const std::filesystem::path shaderSources = gpu::shaderSourceDirectory();
  if (!shaderSources.empty() && std::filesystem::is_directory(shaderSources))
    reloader_ = std::make_unique<gpu::ShaderReloader>(shaderSources, std::filesystem::path(), gpu::pluginSourceDirectory());
  std::filesystem::path first = scene.value_or(gpu::contentDirectory() / "atrium.gltf");
  // `twinlight CAPTURE_FOLDER`: the capture's buffers, no scene at all.
  if (std::filesystem::exists(first / "manifest.json")) {
    openCapture(first);
    return;
  }
  session_->settings().materials = materials;
  // The first scene opens as every scene does (scene_document.cpp), before the first frame so a
  // script starts on it.
  beginOpen({first, std::move(lighting)});
  load_.wait();
  finishLoad();
  try {
    session_->setPath(settings_.lightingPath);
  } catch (const std::exception&) {
    settings_.lightingPath = session_->path();
  }
}

EditorApp::~EditorApp() {
  if (session_) {
    // Everything that works for the scene stops before the engine's device goes (a bake's
    // batches, the compare's FLIP, the frames under way; run() did this already on a clean quit).
    try {
      stopSceneWork("quitting", true);
    } catch (const std::exception&) {
    }
    try {
      session_->finishFrame();
    } catch (const std::exception&) {
    }
    session_->device().waitIdle();
  }
  if (presenter_) presenter_->stop();  // its thread draws with Dear ImGui's backend
  if (uiDevice_) uiDevice_->waitIdle();
  if (load_.valid()) load_.wait();
  for (auto& f : abandonedLoads_) f.wait();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  presenter_.reset();
  imguiPool_.reset();
  if (surface_) vkDestroySurfaceKHR(uiDevice_->instance(), surface_, nullptr);
  session_.reset();
  uiDevice_.reset();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

namespace {

// The engine's device is created on a thread of lower CPU priority: lavapipe's queue and
// rasterizer threads, which start with the device, inherit it (Linux threads inherit their
// creator's nice value), so when the CPU is short the interface's own drawing goes first and
// the engine takes the rest. A failure to lower it changes nothing else.
std::unique_ptr<session::Session> makeEngineSession() {
  constexpr int kEngineNice = 5;
  std::unique_ptr<session::Session> made;
  std::exception_ptr failure;
  std::thread([&] {
    setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), getpriority(PRIO_PROCESS, 0) + kEngineNice);
    // OpenImageIO's worker pool (the Compare panel's FLIP, image writes) starts here too.
    OIIO::default_thread_pool();
    try {
      made = std::make_unique<session::Session>();
    } catch (...) {
      failure = std::current_exception();
    }
  }).join();
  if (failure) std::rethrow_exception(failure);
  return made;
}

}  // namespace

void EditorApp::createWindow() {
  if (!glfwInit()) throw std::runtime_error("cannot open a window (GLFW could not initialise the display)");
  if (!glfwVulkanSupported()) throw std::runtime_error("GLFW found no Vulkan loader for windows");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(settings_.windowWidth, settings_.windowHeight, "Twinlight", nullptr, nullptr);
  if (!window_) throw std::runtime_error("cannot create the editor window");
  input_.attach(window_);
  glfwSetDropCallback(window_, onDrop);
  glfwSetWindowRefreshCallback(window_, onRefresh);

  gpu::DeviceOptions options;
  uint32_t n = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&n);
  for (uint32_t i = 0; i < n; ++i) options.instanceExtensions.emplace_back(exts[i]);
  options.swapchain = true;
  uiDevice_ = std::make_unique<gpu::Device>(options);
  session_ = makeEngineSession();
  checkVk(glfwCreateWindowSurface(uiDevice_->instance(), window_, nullptr, &surface_));
  int w, h;
  glfwGetFramebufferSize(window_, &w, &h);
  presenter_ = std::make_unique<WindowPresenter>(*uiDevice_, surface_, VkExtent2D{uint32_t(w), uint32_t(h)}, settings_.vsync);
}

void EditorApp::initImgui() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  std::error_code ec;
  std::filesystem::create_directories(configDirectory(), ec);
  imguiIniPath = (configDirectory() / "imgui.ini").string();
  io.IniFilename = imguiIniPath.c_str();
  ImGui::StyleColorsDark();
  // Opaque panels: text of a panel behind a floating one does not show through and mix with it.
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  ImGui::GetStyle().WindowRounding = 2.0f;
  // No backend callbacks: input reaches Dear ImGui through the queue (input_queue.h).
  ImGui_ImplGlfw_InitForVulkan(window_, false);

  auto& d = *uiDevice_;
  imguiPool_ = std::make_unique<gpu::DescriptorPool>(d, 64, "ui.descriptors");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = d.instance();
  info.PhysicalDevice = d.physical();
  info.Device = d.handle();
  info.QueueFamily = d.queueFamily();
  info.Queue = d.queue();
  info.DescriptorPool = imguiPool_->handle();
  info.MinImageCount = 2;
  info.ImageCount = presenter_->swapchain().imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkVk;
  ImGui_ImplVulkan_Init(&info, presenter_->swapchain().renderPass());
  d.immediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  // From here on the window's device is the presenter's thread's alone.
  presenter_->start();
}

int EditorApp::run() {
  lastTime_ = glfwGetTime();
  while (!quit_) frame();
  // The user answered for the unsaved work (saved or discarded it; a script's quit discards):
  // the recovery file goes, unless the recovery it offered was never answered.
  if (session_->hasScene() && !recoveryOffer_) session::removeRecovery(recoveryPath());
  stopSceneWork("quitting", true);
  saveSettingsIfChanged();
  presenter_->finish();  // a screenshot asked for last is written, its validation counted
  if (script_ && script_->failed()) {
    fmt::print(stderr, "twinlight: error: script: {}\n", script_->failure());
    return 1;
  }
  try {
    session_->finishFrame();  // its validation messages count too
  } catch (const std::exception&) {
  }
  const uint32_t validation = session_->validationErrors() + uiDevice_->validationErrorCount();
  if (validation > 0) {
    fmt::print(stderr, "twinlight: error: {} Vulkan validation error(s)\n", validation);
    return 1;
  }
  return 0;
}

double EditorApp::fps() const {
  if (frameHistory_.empty()) return 0.0;
  double sum = 0.0;
  size_t n = std::min<size_t>(frameHistory_.size(), 30);
  for (size_t i = frameHistory_.size() - n; i < frameHistory_.size(); ++i) sum += frameHistory_[i];
  return sum > 0.0 ? 1000.0 * double(n) / sum : 0.0;
}

void EditorApp::refreshShownFigures(double now) {
  constexpr double kRefreshSeconds = 0.5;
  if (figures_.at >= 0.0 && now - figures_.at < kRefreshSeconds) return;
  figures_.uiFps = fps();
  const uint64_t presented = framesPresented();
  figures_.presentedFps = figures_.at < 0.0 ? 0.0 : double(presented - presentedAtFigures_) / (now - figures_.at);
  presentedAtFigures_ = presented;
  figures_.engineFps = engineFps();
  figures_.frameAgeMs = 1000.0 * shownFrameAge();
  figures_.passMs.assign(frameHistory_.begin(), frameHistory_.end());
  figures_.at = now;
}

double EditorApp::engineFps() const {
  if (engineFrameEnds_.size() < 2) return 0.0;
  const double span = engineFrameEnds_.back() - engineFrameEnds_.front();
  return span > 0.0 ? double(engineFrameEnds_.size() - 1) / span : 0.0;
}

double EditorApp::shownFrameAge() const { return shownBegunAt_ < 0.0 ? 0.0 : glfwGetTime() - shownBegunAt_; }

bool EditorApp::engineActive() const {
  return (session_->hasScene() || session_->hasCapture()) && viewportSize_.x >= 1.0f && viewportSize_.y >= 1.0f;
}

void EditorApp::frame() {
  const double frameStart = glfwGetTime();
  glfwPollEvents();
  int w, h;
  glfwGetFramebufferSize(window_, &w, &h);
  if (w == 0 || h == 0) {  // minimised: nothing to draw, do not spin
    glfwWaitEventsTimeout(0.1);
    return;
  }
  double now = glfwGetTime();
  float seconds = float(now - lastTime_);
  lastTime_ = now;

  // The window's close button asks first, as File > Quit does.
  if (glfwWindowShouldClose(window_)) {
    glfwSetWindowShouldClose(window_, GLFW_FALSE);
    askToQuit();
  }
  if (!droppedFiles.empty()) openScene(droppedFiles.back());  // one scene at a time: the last one dropped
  droppedFiles.clear();
  if (load_.valid() && load_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) finishLoad();
  std::erase_if(abandonedLoads_, [](auto& f) { return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready; });
  collectEngineFrame();
  if (!load_.valid() && sceneWatcher_.changed(now)) reloadScene();
  if (script_) script_->step(*this);
  // A bake uses the engine's device between its frames (its batches wait for their own work).
  if (!session_->frameInFlight()) stepAlbedoBake();
  if (uiFrames_ % 15 == 0) pollShaders(), saveSettingsIfChanged();
  updateWindowTitle();
  autosave(now);
  pollTune();
  refreshShownFigures(now);

  const double panelsStart = glfwGetTime();
  profile_.input += panelsStart - frameStart;
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  input_.feed(ImGui::GetIO());
  ImGui::NewFrame();
  drawPanels(*this);
  // Whatever changed a setting or the light this frame (a widget, Paste JSON, a script) is
  // one undo step; a drag under way folds into the step it began.
  if (session_->hasScene() && !load_.valid()) {
    // Only a change after the first of the same press folds into its step: the first change of
    // a new drag starts one of its own (else it would join the edit before it).
    const bool active = ImGui::IsAnyItemActive() || gizmoDrag_;
    if (active && !interactionActive_) interactionChanged_ = false;
    const bool changed = history_.observe(session_->settings(), session_->lighting(), active && interactionChanged_);
    interactionChanged_ = interactionChanged_ || (active && changed);
    interactionActive_ = active;
  }
  handleCameraInput(seconds);
  if (playing_ && session_->animated() && !load_.valid())
    session_->setAnimationTime(std::fmod(session_->animationTime() + seconds, std::max(session_->scene().animationSeconds, 1e-3)));
  startEngineFrame();
  ImGui::Render();
  const double presentStart = glfwGetTime();
  profile_.panels += presentStart - panelsStart;
  presentIfChanged();
  profile_.present += glfwGetTime() - presentStart;

  ++uiFrames_;
  frameHistory_.push_back(seconds * 1000.0);
  if (frameHistory_.size() > 240) frameHistory_.pop_front();
  // At most 60 UI frames a second, 40 while the engine renders (above the 30 an artist
  // needs): what the interface does not need, the engine gets (on a software device both
  // share the CPU). Passes are paced against a running deadline, so a wake-up that comes
  // late on a loaded machine is made up by the next wait instead of lowering the rate. The
  // wait takes the window's events as they come (into the input queue, in order), so nothing
  // is lost between passes.
  const double frameBudget = session_->frameInFlight() ? 1.0 / 40.0 : 1.0 / 60.0;
  const double sleepStart = glfwGetTime();
  // Late by more than a pass (a stall): at most one pass is made up, not the whole stall.
  nextPassAt_ = std::max(nextPassAt_ + frameBudget, sleepStart - frameBudget);
  for (double spare = nextPassAt_ - sleepStart; spare > 0.0; spare = nextPassAt_ - glfwGetTime()) glfwWaitEventsTimeout(spare);
  profile_.sleep += glfwGetTime() - sleepStart;
}

// Hands the window's thread a frame when what the window would show changed: the UI loop
// never waits for the drawing (on lavapipe presenting waits until the frame is drawn).
void EditorApp::presentIfChanged() {
  for (const std::string& e : presenter_->takeErrors()) showError(e);
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  const bool clearImage = imageShown_ && !session_->hasScene() && !session_->hasCapture();
  if (clearImage) imageShown_ = false, shownImage_.clear(), newImage_.reset();
  uint64_t hash = drawDataHash(*ImGui::GetDrawData());
  hash = scene::hashBytes(&viewportMin_, sizeof viewportMin_, hash);
  hash = scene::hashBytes(&viewportSize_, sizeof viewportSize_, hash);
  const int32_t window[3] = {w, h, settings_.vsync ? 1 : 0};
  hash = scene::hashBytes(window, sizeof window, hash);
  redraw_.observe(hash);
  if (newImage_ || clearImage || windowExposed || screenshotPath_) redraw_.invalidate();
  windowExposed = false;
  if (!redraw_.take()) return;
  WindowPresenter::Frame frame;
  frame.ui = DrawDataCopy(*ImGui::GetDrawData());
  frame.viewportMin = glm::ivec2(viewportMin_);
  frame.viewportMax = glm::ivec2(viewportMin_ + viewportSize_);
  frame.windowSize = {uint32_t(w), uint32_t(h)};
  frame.vsync = settings_.vsync;
  frame.image = std::move(newImage_);
  frame.clearImage = clearImage;
  frame.screenshot = std::move(screenshotPath_);
  newImage_.reset(), screenshotPath_.reset();
  presenter_->submit(std::move(frame));
}

void EditorApp::handleCameraInput(float seconds) {
  if (!session_->hasScene()) return;
  ImGuiIO& io = ImGui::GetIO();
  glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
  glm::vec2 delta = mouse - lastMouse_;
  lastMouse_ = mouse;
  CameraInput in;
  in.seconds = seconds;
  in.fast = ImGui::IsKeyDown(GLFW_KEY_LEFT_SHIFT) || ImGui::IsKeyDown(GLFW_KEY_RIGHT_SHIFT);

  // The compare view's wipe line: a press on it drags the line instead of the camera.
  if (compareView_ && !compareView_->difference && viewportHovered_ && ImGui::IsMouseClicked(0) &&
      std::abs(mouse.x - (viewportMin_.x + compareView_->wipe * viewportSize_.x)) < 8.0f)
    draggingWipe_ = true;
  if (draggingWipe_) {
    if (ImGui::IsMouseDown(0) && compareView_ && viewportSize_.x > 0.0f)
      compareView_->wipe = std::clamp((mouse.x - viewportMin_.x) / viewportSize_.x, 0.0f, 1.0f);
    else
      draggingWipe_ = false;
    camera_.update(in);
    return;
  }
  // Light icons and gizmo handles take a press before the camera and the instance pick do.
  if (handleLightOverlayInput(mouse)) {
    camera_.update(in);
    return;
  }
  if (viewportHovered_ && ImGui::IsMouseClicked(0)) pressPos_ = mouse, dragged_ = false;
  if (ImGui::IsMouseDown(0) && viewportHovered_) {
    if (glm::length(mouse - pressPos_) > 3.0f) dragged_ = true;
    if (dragged_) in.orbitDelta = delta;
  }
  if (ImGui::IsMouseReleased(0) && viewportHovered_ && !dragged_) clickViewport(mouse);
  if (ImGui::IsMouseDown(2) && viewportHovered_) in.panDelta = delta;
  if (viewportHovered_ && io.MouseWheel != 0.0f && !io.KeyCtrl) in.dolly = io.MouseWheel;
  if (viewportHovered_ && io.MouseWheel != 0.0f && io.KeyCtrl) {
    // Ctrl + wheel zooms the viewer around the cursor: the texel under it stays put.
    const glm::vec2 uv = (mouse - viewportMin_) / viewportSize_;
    const glm::vec4 before = viewerWindow(viewer_);
    const glm::vec2 texel = glm::vec2(before) + uv * glm::vec2(before.z, before.w);
    viewer_.zoom = std::clamp(viewer_.zoom * std::exp2(0.25f * io.MouseWheel), 1.0f, 256.0f);
    const glm::vec4 after = viewerWindow(viewer_);
    viewer_.centre = texel - (uv - 0.5f) * glm::vec2(after.z, after.w);
  }
  const bool flying = ImGui::IsMouseDown(1) && viewportHovered_;
  if (flying) {
    in.lookDelta = delta;
    auto key = [&](int k) { return ImGui::IsKeyDown(k) ? 1.0f : 0.0f; };
    in.move = {key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q), key(GLFW_KEY_W) - key(GLFW_KEY_S)};
  }
  camera_.update(in);

  if (!io.WantTextInput && !flying) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) focusSelection();
    if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) showHelp_ = !showHelp_;
    if (ImGui::IsKeyPressed(GLFW_KEY_F2, false)) showBuffers_ = !showBuffers_;
    if (ImGui::IsKeyPressed(GLFW_KEY_F3, false)) showCompare_ = !showCompare_;
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false) && gpu::RenderDoc::get().attached()) requestRenderDocCapture();
    bool ctrl = io.KeyCtrl;
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_O, false)) showBrowser_ = true;
    // Undo and redo: settings, lighting and albedo edits, the latest first; save all of them.
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false)) io.KeyShift ? redo() : undo();
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false)) redo();
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S, false)) saveWork();
    for (int slot = 1; slot <= 9; ++slot)
      if (ImGui::IsKeyPressed(GLFW_KEY_0 + slot, false)) applyBookmark(slot, ctrl);
  }
}

void EditorApp::setCompare(bool on) {
  if (!on) {
    compareView_.reset();
    return;
  }
  session::CompareView v;
  // The path in use against another real-time one with history (what an artist usually
  // weighs), else the last such path; failing that, any other path that is not the reference.
  std::vector<std::string> realTime, others;
  for (const auto& p : session_->paths()) {
    if (!p.available || p.capabilities.isReference || p.capabilities.debugView) continue;
    (p.capabilities.accumulates ? realTime : others).push_back(p.name);
  }
  const bool current = std::find(realTime.begin(), realTime.end(), session_->path()) != realTime.end();
  v.left = current ? session_->path() : (realTime.empty() ? session_->path() : realTime.back());
  for (const auto* list : {&realTime, &others})
    for (const auto& name : *list)
      if (v.right.empty() && name != v.left) v.right = name;
  if (v.right.empty()) v.right = v.left;
  compareView_ = v;
  showCompare_ = true;
}

void EditorApp::focusSelection() {
  if (!session_->hasScene()) return;
  const auto& s = session_->scene();
  camera_.focus(selected_ && *selected_ < s.instances.size() ? s.instances[*selected_].worldBounds : s.bounds);
}

std::string EditorApp::sceneKey() const {
  return session_->hasScene() ? std::filesystem::absolute(session_->scene().path).string() : "";
}

// Settings are written when they change (checked every few frames), not only on a clean
// exit: a crash or a killed editor keeps the path, render scale, recent scenes, bookmarks.
void EditorApp::saveSettingsIfChanged() {
  int w, h;
  glfwGetWindowSize(window_, &w, &h);
  if (w > 0 && h > 0) settings_.windowWidth = w, settings_.windowHeight = h;
  nlohmann::json now = toJson(settings_);
  if (now == savedSettings_) return;
  try {
    saveSettings(settings_);
  } catch (const std::exception& e) {
    // Said once per change (not retried every few frames); the editor works on without it.
    spdlog::warn("editor settings not saved: {}", e.what());
    showError(fmt::format("settings not saved: {}", e.what()));
  }
  savedSettings_ = std::move(now);
}

void EditorApp::applyBookmark(int slot, bool save) {
  auto& marks = settings_.bookmarks[sceneKey()];
  std::string key = std::to_string(slot);
  if (save) {
    marks[key] = camera_.save();
    saveSettingsIfChanged();
  } else if (marks.contains(key)) {
    try {
      camera_.load(marks[key]);
    } catch (const std::exception&) {
      showError(fmt::format("camera bookmark {} is damaged", slot));
    }
  }
}

void EditorApp::clickViewport(glm::vec2 windowPos) {
  if (windowPos.x < viewportMin_.x || windowPos.y < viewportMin_.y || windowPos.x >= viewportMin_.x + viewportSize_.x ||
      windowPos.y >= viewportMin_.y + viewportSize_.y)
    return;
  pendingClick_ = windowPos;
}

void EditorApp::setPath(const std::string& name) {
  try {
    session_->setPath(name);
    settings_.lightingPath = name;
  } catch (const std::exception& e) {
    showError(e.what());
  }
}

std::filesystem::path EditorApp::defaultCaptureFolder() const {
  const std::string scene = session_->hasScene() ? session_->scene().name : "none";
  return std::filesystem::path("captures") / fmt::format("{}-{}-frame{}", scene, session_->path(), session_->frameIndex());
}

void EditorApp::openAlbedoDatabase(const std::filesystem::path& file) {
  attachAlbedoDatabase(file);
  if (session_->albedo().orphanCount()) notifyOrphans();
}

std::string EditorApp::undo() {
  auto& albedo = session_->albedo();
  const auto settingsAt = history_.undoTime(), albedoAt = albedo.undoTime();
  if (!settingsAt && !albedoAt) return {};
  if (albedoAt && (!settingsAt || *albedoAt > *settingsAt)) {
    albedo.undo();
    return "undid an albedo edit";
  }
  const std::string what = history_.undoLabel();
  session::Lighting lighting = session_->lighting();
  history_.undo(session_->settings(), lighting);
  session_->setLighting(lighting);
  notify("undid " + what);
  return "undid " + what;
}

std::string EditorApp::redo() {
  auto& albedo = session_->albedo();
  const auto settingsAt = history_.redoTime(), albedoAt = albedo.redoTime();
  if (!settingsAt && !albedoAt) return {};
  if (albedoAt && (!settingsAt || *albedoAt < *settingsAt)) {
    albedo.redo();
    return "redid an albedo edit";
  }
  const std::string what = history_.redoLabel();
  session::Lighting lighting = session_->lighting();
  history_.redo(session_->settings(), lighting);
  session_->setLighting(lighting);
  notify("redid " + what);
  return "redid " + what;
}

void EditorApp::notifyOrphans() {
  const size_t n = session_->albedo().orphanCount();
  notify(fmt::format("{} albedo override{} reach{} no mesh + material of this scene: see Albedo > Orphaned overrides", n,
                     n == 1 ? "" : "s", n == 1 ? "es" : ""));
}

void EditorApp::attachAlbedoDatabase(const std::filesystem::path& file) {
  if (bake_) throw session::SessionError("a bake is running: cancel it first");
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  // Attaching drops the library's unsaved edits: they are carried over onto the new database
  // as edits (unsaved there until saved), never lost to a database switch.
  const std::vector<session::RecoveredOverride> carried = session_->hasScene() ? unsavedOverrides() : std::vector<session::RecoveredOverride>{};
  session_->openAlbedoDatabase(file);
  applyOverrides(carried);
  if (!carried.empty())
    notify(fmt::format("{} unsaved albedo edit{} carried over to {}", carried.size(), carried.size() == 1 ? "" : "s",
                       file.filename().string()));
  albedoDbField_ = file.string();
  // Remembered for the scene: reopened when the scene is loaded again.
  if (session_->hasScene()) settings_.albedoDatabases[sceneKey()] = std::filesystem::absolute(file).string();
}

// The scene's database from the last session, if it still exists (the RT path's hits use it).
void EditorApp::reopenAlbedoDatabase() {
  const std::string key = sceneKey();
  if (!settings_.albedoDatabases.contains(key) || !settings_.albedoDatabases[key].is_string()) return;
  const std::filesystem::path file = settings_.albedoDatabases[key].get<std::string>();
  if (!std::filesystem::exists(file)) {
    notify(fmt::format("the albedo database {} of this scene is gone: rays read texture averages", file.string()));
    return;
  }
  try {
    attachAlbedoDatabase(file);
    notify(fmt::format("reopened the albedo database {}", file.string()));
    if (session_->albedo().orphanCount()) notifyOrphans();
  } catch (const std::exception& e) {
    showError(fmt::format("cannot reopen the albedo database {}: {}", file.string(), e.what()));
  }
}

std::filesystem::path EditorApp::defaultAlbedoDatabase() const {
  const std::string key = sceneKey();
  if (settings_.albedoDatabases.contains(key) && settings_.albedoDatabases[key].is_string())
    return settings_.albedoDatabases[key].get<std::string>();
  const uint64_t hash = scene::hashBytes(key.data(), key.size());
  return std::filesystem::path("out") /
         fmt::format("{}-{:08x}.albedo.db", session_->scene().path.stem().string(), uint32_t(hash));
}

void EditorApp::startAlbedoBake(bool force) {
  if (bake_) return;
  albedo::BakeOptions options;
  options.force = force;
  bake_ = session_->startAlbedoBake(options);
  lastBakeSummary_.clear();
}

void EditorApp::stepAlbedoBake() {
  if (!bake_) return;
  try {
    bake_->step();
  } catch (const std::exception& e) {
    showError(fmt::format("albedo bake failed: {}", e.what()));
    bake_.reset();
    session_->albedo().reload();
    return;
  }
  if (!bake_->finished()) return;
  const albedo::BakeProgress& p = bake_->progress();
  lastBakeSummary_ = fmt::format("{}: baked {}, skipped {}, failed {} of {} keys", p.cancelled ? "cancelled" : "done",
                                 p.baked, p.skipped, p.failed, p.total);
  if (p.invisible)
    lastBakeSummary_ += fmt::format("; {} not visible from any direction (fully cut out or empty: nothing to bake)", p.invisible);
  for (const std::string& f : p.failures) lastBakeSummary_ += "\nfailed: " + f;
  bake_.reset();
  session_->albedo().reload();  // the new rows apply from the next frame
}

void EditorApp::requestRenderDocCapture() {
  auto& rd = gpu::RenderDoc::get();
  if (!rd.attached()) throw session::SessionError("RenderDoc capture unavailable: " + rd.unavailableReason());
  const std::string scene = session_->hasScene() ? session_->scene().name : "none";
  rd.setCaptureTemplate((std::filesystem::absolute("captures") / "renderdoc" / scene).string());
  renderDocPending_ = true;  // the next engine frame
}

void EditorApp::notify(const std::string& text) {
  notices_.push_back({text, glfwGetTime()});
  if (notices_.size() > 50) notices_.pop_front();
}

const EditorApp::Notice* EditorApp::recentNotice() const {
  constexpr double kShownSeconds = 8.0;
  return !notices_.empty() && glfwGetTime() - notices_.back().time < kShownSeconds ? &notices_.back() : nullptr;
}

void EditorApp::pollShaders() {
  if (!reloader_) return;
  gpu::ShaderReloadResult r = reloader_->poll();
  if (!r.recompiled.empty())
    shaderStatus_ = fmt::format("reloaded {}{}", r.recompiled.front(),
                                r.recompiled.size() > 1 ? fmt::format(" and {} more", r.recompiled.size() - 1) : "");
  if (!r.errors.empty()) shaderStatus_ = "shader error (see the Shader errors window)";
}

void EditorApp::openCapture(const std::filesystem::path& dir) {
  try {
    session_->openCapture(dir);
    sceneWatcher_.watch({}, 0.0);  // the capture replaced the scene
    showBuffers_ = true;
    pinPreview("");
    selected_.reset();
  } catch (const std::exception& e) {
    showError(e.what());
  }
}

}  // namespace tl::editor
