#include "editor_app.h"

#include "gpu/install_paths.h"
#include "gpu/renderdoc.h"
#include "session/capture.h"

#include "script.h"

#include <GLFW/glfw3.h>
#include <OpenImageIO/imageio.h>
#include <cmath>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>
#include <spdlog/spdlog.h>

#include <cstring>

namespace tl::editor {

void drawPanels(EditorApp& app);

namespace {

std::string imguiIniPath;  // ImGui keeps the pointer: it must outlive the context
std::vector<std::string> droppedFiles;

void onDrop(GLFWwindow*, int count, const char** paths) {
  for (int i = 0; i < count; ++i) droppedFiles.emplace_back(paths[i]);
}

void checkVk(VkResult r) {
  if (r != VK_SUCCESS) throw gpu::Error(fmt::format("Dear ImGui's Vulkan backend: {}", gpu::resultName(r)));
}

}  // namespace

EditorApp::EditorApp(std::optional<std::filesystem::path> scene, std::optional<std::filesystem::path> script,
                     lighting::MaterialMode materials) {
  settings_ = loadSettings();
  browserDir_ = std::filesystem::current_path();
  createWindow();
  initImgui();
  if (script) script_ = std::make_unique<Script>(*script);
  // Edit a shader under shaders/ while the editor runs: it is recompiled and swapped in.
  // An installed program without the source tree has none to watch.
  const std::filesystem::path shaderSources = gpu::shaderSourceDirectory();
  if (!shaderSources.empty() && std::filesystem::is_directory(shaderSources))
    reloader_ = std::make_unique<gpu::ShaderReloader>(shaderSources);
  std::filesystem::path first = scene.value_or(gpu::contentDirectory() / "atrium.gltf");
  // `twinlight CAPTURE_FOLDER`: the capture's buffers, no scene at all.
  if (std::filesystem::exists(first / "manifest.json")) {
    openCapture(first);
    return;
  }
  session_->settings().materials = materials;
  // The first scene loads before the first frame so a script starts on a loaded scene.
  try {
    session_->loadScene(first);
    camera_.reset(session_->view(), glm::length(session_->scene().bounds.size()));
    settings_.addRecent(std::filesystem::absolute(first).string());
  } catch (const std::exception& e) {
    showError(e.what());
  }
  try {
    session_->setPath(settings_.lightingPath);
  } catch (const std::exception&) {
    settings_.lightingPath = session_->path();
  }
}

EditorApp::~EditorApp() {
  if (session_) session_->device().waitIdle();
  if (load_.valid()) load_.wait();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  swapchain_.reset();
  imguiPool_.reset();
  if (surface_) vkDestroySurfaceKHR(session_->device().instance(), surface_, nullptr);
  session_.reset();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void EditorApp::createWindow() {
  if (!glfwInit()) throw std::runtime_error("cannot open a window (GLFW could not initialise the display)");
  if (!glfwVulkanSupported()) throw std::runtime_error("GLFW found no Vulkan loader for windows");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(settings_.windowWidth, settings_.windowHeight, "Twinlight", nullptr, nullptr);
  if (!window_) throw std::runtime_error("cannot create the editor window");
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, onDrop);
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) {
    static_cast<EditorApp*>(glfwGetWindowUserPointer(w))->resized_ = true;
  });

  gpu::DeviceOptions options;
  uint32_t n = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&n);
  for (uint32_t i = 0; i < n; ++i) options.instanceExtensions.emplace_back(exts[i]);
  options.swapchain = true;
  session_ = std::make_unique<session::Session>(options);
  checkVk(glfwCreateWindowSurface(session_->device().instance(), window_, nullptr, &surface_));
  int w, h;
  glfwGetFramebufferSize(window_, &w, &h);
  swapchain_ = std::make_unique<gpu::Swapchain>(session_->device(), surface_, VkExtent2D{uint32_t(w), uint32_t(h)},
                                                settings_.vsync);
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
  ImGui::GetStyle().WindowRounding = 2.0f;
  ImGui_ImplGlfw_InitForVulkan(window_, true);

  auto& d = session_->device();
  imguiPool_ = std::make_unique<gpu::DescriptorPool>(d, 64, "ui.descriptors");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = d.instance();
  info.PhysicalDevice = d.physical();
  info.Device = d.handle();
  info.QueueFamily = d.queueFamily();
  info.Queue = d.queue();
  info.DescriptorPool = imguiPool_->handle();
  info.MinImageCount = 2;
  info.ImageCount = swapchain_->imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkVk;
  ImGui_ImplVulkan_Init(&info, swapchain_->renderPass());
  d.immediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

int EditorApp::run() {
  lastTime_ = glfwGetTime();
  while (!glfwWindowShouldClose(window_) && !quit_) frame();
  int w, h;
  glfwGetWindowSize(window_, &w, &h);
  if (w > 0 && h > 0) settings_.windowWidth = w, settings_.windowHeight = h;
  saveSettings(settings_);
  if (script_ && script_->failed()) {
    fmt::print(stderr, "twinlight: error: script: {}\n", script_->failure());
    return 1;
  }
  if (session_->validationErrors() > 0) {
    fmt::print(stderr, "twinlight: error: {} Vulkan validation error(s)\n", session_->validationErrors());
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

void EditorApp::frame() {
  glfwPollEvents();
  int w, h;
  glfwGetFramebufferSize(window_, &w, &h);
  if (w == 0 || h == 0) {  // minimised: nothing to draw, do not spin
    glfwWaitEventsTimeout(0.1);
    return;
  }
  if (resized_ || swapchain_->extent().width != uint32_t(w) || swapchain_->extent().height != uint32_t(h)) {
    swapchain_->recreate({uint32_t(w), uint32_t(h)}, settings_.vsync);
    resized_ = false;
  }
  double now = glfwGetTime();
  float seconds = float(now - lastTime_);
  lastTime_ = now;

  for (auto& f : droppedFiles) openScene(f);
  droppedFiles.clear();
  if (load_.valid() && load_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) finishLoad();
  if (script_) script_->step(*this);
  stepAlbedoBake();
  if (framesDrawn_ % 15 == 0) pollShaders();

  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  drawPanels(*this);
  handleCameraInput(seconds);
  if (playing_ && session_->animated() && !load_.valid())
    session_->setAnimationTime(std::fmod(session_->animationTime() + seconds, std::max(session_->scene().animationSeconds, 1e-3)));
  renderEngine();
  ImGui::Render();
  recordAndPresent();

  ++framesDrawn_;
  frameHistory_.push_back(seconds * 1000.0);
  if (frameHistory_.size() > 240) frameHistory_.pop_front();
}

void EditorApp::handleCameraInput(float seconds) {
  if (!session_->hasScene()) return;
  ImGuiIO& io = ImGui::GetIO();
  glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
  glm::vec2 delta = mouse - lastMouse_;
  lastMouse_ = mouse;
  CameraInput in;
  in.seconds = seconds;
  in.fast = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;

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
    const float size = 1.0f / viewer_.zoom;
    viewer_.centre = texel - (uv - 0.5f) * size;
  }
  const bool flying = ImGui::IsMouseDown(1) && viewportHovered_;
  if (flying) {
    in.lookDelta = delta;
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
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
    // Albedo edits (the inspector's override): undo, redo, save.
    auto& albedo = session_->albedo();
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false)) io.KeyShift ? albedo.redo() : albedo.undo();
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false)) albedo.redo();
    if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S, false) && albedo.database() && albedo.unsaved()) {
      try {
        albedo.save();
      } catch (const std::exception& e) {
        showError(e.what());
      }
    }
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
    if (!p.available || p.capabilities.isReference) continue;
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

void EditorApp::applyBookmark(int slot, bool save) {
  auto& marks = settings_.bookmarks[sceneKey()];
  std::string key = std::to_string(slot);
  if (save) {
    marks[key] = camera_.save();
    saveSettings(settings_);
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

void EditorApp::openScene(const std::filesystem::path& file) {
  if (load_.valid()) return;  // one load at a time
  loadingPath_ = file;
  load_ = std::async(std::launch::async, [file] { return session::Session::parseScene(file); });
}

void EditorApp::cancelLoad() {
  // Parsing cannot be interrupted safely; its result is dropped when it arrives.
  if (!load_.valid()) return;
  std::thread([f = std::move(load_)]() mutable {
    try {
      f.get();
    } catch (...) {
    }
  }).detach();
  load_ = {};
}

void EditorApp::finishLoad() {
  try {
    session_->installScene(load_.get());
    camera_.reset(session_->view(), glm::length(session_->scene().bounds.size()));
    selected_.reset();
    preview_.clear();
    settings_.addRecent(std::filesystem::absolute(loadingPath_).string());
    saveSettings(settings_);
  } catch (const std::exception& e) {
    showError(e.what());
  }
  load_ = {};
}

std::filesystem::path EditorApp::defaultCaptureFolder() const {
  const std::string scene = session_->hasScene() ? session_->scene().name : "none";
  return std::filesystem::path("captures") / fmt::format("{}-{}-frame{}", scene, session_->path(), session_->frameIndex());
}

void EditorApp::renderEngine() {
  const bool capture = session_->hasCapture();
  if ((!session_->hasScene() && !capture) || viewportSize_.x < 1.0f || viewportSize_.y < 1.0f) return;
  uint32_t w = std::max(1u, uint32_t(viewportSize_.x * settings_.renderScale));
  uint32_t h = std::max(1u, uint32_t(viewportSize_.y * settings_.renderScale));
  try {
    if (capture) pendingClick_.reset(), frameCapturePath_.reset();  // a reopened capture has no live frame
    if (!capture && (w != session_->settings().width || h != session_->settings().height)) session_->setSize(w, h);
    if (!capture) session_->setView(camera_.view());
    VkFormat hoverFormat = VK_FORMAT_UNDEFINED;
    std::string decoder;
    uint64_t texels = 0;
    for (const auto& r : session_->resources()) {
      if (r.name == preview_) hoverFormat = r.desc.format;
      if (r.name == viewer_.resource)
        decoder = r.desc.decoder, texels = uint64_t(r.desc.extent.width) * r.desc.extent.height * r.desc.extent.depth;
    }
    // Live read-back of big volumes (the voxel clipmap) would cost more than the frame.
    const bool liveReadback = showBuffers_ && viewer_.live && texels <= (uint64_t(1) << 22);
    lighting::DisplayRequest display = displayRequest(viewer_, preview_, hoverFormat, std::exp2(-session_->exposureEv()));
    display.selectedInstance = selected_ ? *selected_ + 1 : 0;
    session_->setDisplay(display);
    // The viewer's read-back (histogram, probe, range fit): the shown resource and what its
    // decoder needs beside it.
    std::vector<std::string> viewerReads;
    if (preview_.empty() && !viewer_.resource.empty() &&
        (viewer_.autoFitPending || viewer_.refresh || viewer_.keepCopy || liveReadback)) {
      viewerReads.push_back(viewer_.resource);
      for (const std::string& c : lighting::decoderCompanions(decoder)) viewerReads.push_back(c);
    }
    if (!capture) {
      try {
        session_->setCompareView(compareView_);
      } catch (const session::SessionError& e) {
        compareView_.reset();
        session_->setCompareView(std::nullopt);
        showError(e.what());
      }
    }
    for (const std::string& n : viewerReads) session_->requestBuffer(n);
    if (pendingClick_) session_->requestBuffer("gbuffer.instanceId");
    if (captureRequested_) session_->requestBuffer(lighting::kDisplayLdr);
    if (frameCapturePath_) session_->requestAllBuffers();
    session_->renderFrames(1);
    if (frameCapturePath_) {
      const std::filesystem::path dir = *frameCapturePath_;
      frameCapturePath_.reset();
      auto manifest = session::writeCapture(*session_, dir);
      size_t files = 0;
      for (const auto& r : manifest["resources"]) files += !r["file"].is_null();
      fmt::print("captured {} of {} resources into {}\n", files, manifest["resources"].size(), dir.string());
    }
    if (captureRequested_) {
      capture_ = session_->buffer(lighting::kDisplayLdr).texels();
      captureRequested_ = false;
    }
    if (!viewerReads.empty()) {
      viewer_.readbacks.clear();
      for (const std::string& n : viewerReads) viewer_.readbacks[n] = session_->buffer(n);
      const graph::Readback& shown = viewer_.readbacks[viewer_.resource];
      if (viewer_.autoFitPending && shown.extent.width > 0) {
        std::tie(viewer_.rangeMin, viewer_.rangeMax) = fitRange(channelValues(shown, viewer_.channel, viewer_.slice));
        viewer_.autoFitPending = false;
      }
      if (viewer_.keepCopy) viewer_.copyOf = viewer_.resource, viewer_.copyReadback = shown;
      viewer_.refresh = viewer_.keepCopy = false;
    }
    if (pendingClick_) {
      glm::vec2 uv = (*pendingClick_ - viewportMin_) / viewportSize_;
      selected_ = session_->instanceAt(uint32_t(uv.x * w), uint32_t(uv.y * h));
      pendingClick_.reset();
    }
  } catch (const std::exception& e) {
    showError(e.what());
    preview_.clear();
    viewer_.resource.clear();
    viewer_.keepCopy = viewer_.showCopy = false;
    pendingClick_.reset();
  }
}

void EditorApp::recordAndPresent() {
  auto& d = session_->device();
  if (!swapchain_->acquire()) {
    resized_ = true;
    return;
  }
  VkCommandBuffer cmd = d.beginCommands();
  VkImage target = swapchain_->image();
  VkExtent2D ext = swapchain_->extent();
  gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkClearColorValue clear{{0.09f, 0.09f, 0.10f, 1.0f}};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);

  // The engine's image, scaled into the viewport panel (linear filter: render scale).
  const gpu::Image* display = session_->hasScene() || session_->hasCapture() ? session_->displayImage() : nullptr;
  if (display && viewportSize_.x >= 1.0f && viewportSize_.y >= 1.0f && !load_.valid()) {
    VkImageLayout layout = session_->displayImageLayout();
    gpu::transitionImage(cmd, display->handle(), VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    // The blit writes over the clear: it waits for it.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(display->extent().width), int32_t(display->extent().height), 1};
    int32_t x0 = std::clamp(int32_t(viewportMin_.x), 0, int32_t(ext.width));
    int32_t y0 = std::clamp(int32_t(viewportMin_.y), 0, int32_t(ext.height));
    int32_t x1 = std::clamp(int32_t(viewportMin_.x + viewportSize_.x), 0, int32_t(ext.width));
    int32_t y1 = std::clamp(int32_t(viewportMin_.y + viewportSize_.y), 0, int32_t(ext.height));
    if (x1 > x0 && y1 > y0) {
      blit.dstOffsets[0] = {x0, y0, 0};
      blit.dstOffsets[1] = {x1, y1, 1};
      vkCmdBlitImage(cmd, display->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    gpu::transitionImage(cmd, display->handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
  }

  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = swapchain_->renderPass();
  rp.framebuffer = swapchain_->framebuffer();
  rp.renderArea = {{0, 0}, ext};
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);

  std::optional<gpu::Buffer> shot;
  if (screenshotPath_) {
    shot.emplace(d, VkDeviceSize(ext.width) * ext.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                 "ui.screenshot");
    gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {ext.width, ext.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shot->handle(), 1, &region);
    gpu::transitionImage(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  }
  if (!swapchain_->submitAndPresent(cmd)) resized_ = true;
  if (shot) {
    d.wait(swapchain_->lastSubmission());
    writeScreenshot(*shot, ext);
  }
}

void EditorApp::writeScreenshot(const gpu::Buffer& pixels, VkExtent2D ext) {
  std::filesystem::path file = *screenshotPath_;
  screenshotPath_.reset();
  std::vector<uint8_t> rgb(size_t(ext.width) * ext.height * 3);
  const auto* src = static_cast<const uint8_t*>(pixels.mapped());
  const bool bgra = swapchain_->format() == VK_FORMAT_B8G8R8A8_UNORM;
  for (size_t i = 0; i < size_t(ext.width) * ext.height; ++i) {
    rgb[i * 3 + 0] = src[i * 4 + (bgra ? 2 : 0)];
    rgb[i * 3 + 1] = src[i * 4 + 1];
    rgb[i * 3 + 2] = src[i * 4 + (bgra ? 0 : 2)];
  }
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec spec(int(ext.width), int(ext.height), 3, OIIO::TypeDesc::UINT8);
  if (!out || !out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !out->close()) {
    showError(fmt::format("{}: cannot write the screenshot", file.string()));
    return;
  }
  fmt::print("wrote {}\n", std::filesystem::absolute(file).string());
}

void EditorApp::openAlbedoDatabase(const std::filesystem::path& file) {
  if (bake_) throw session::SessionError("a bake is running: cancel it first");
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  session_->openAlbedoDatabase(file);
  albedoDbField_ = file.string();
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
  for (const std::string& f : p.failures) lastBakeSummary_ += "\nfailed: " + f;
  bake_.reset();
  session_->albedo().reload();  // the new rows apply from the next frame
}

void EditorApp::requestRenderDocCapture() {
  auto& rd = gpu::RenderDoc::get();
  if (!rd.attached()) throw session::SessionError("RenderDoc capture unavailable: " + rd.unavailableReason());
  const std::string scene = session_->hasScene() ? session_->scene().name : "none";
  rd.setCaptureTemplate((std::filesystem::absolute("captures") / "renderdoc" / scene).string());
  rd.triggerCapture();  // the next presented frame, engine work included
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
    showBuffers_ = true;
    pinPreview("");
    selected_.reset();
  } catch (const std::exception& e) {
    showError(e.what());
  }
}

}  // namespace tl::editor
