// The editor's engine frames and its own: the UI thread starts an engine frame with the
// input it has, goes on drawing the interface while the engine's device works, and collects
// the frame when it is done (its display image, picking ids, the viewer's read-backs, a
// capture). The window's thread shows the latest finished image (window_presenter.h).
#include "editor_app.h"

#include "gpu/renderdoc.h"
#include "session/capture.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tl::editor {

// How many engine frames may be in flight now. Ordinary frames overlap (the engine records
// frame N+1 while the device runs frame N); a frame that must stand alone does not: a capture
// or a snapshot reads every buffer of its own frame, a RenderDoc frame is bracketed, and a
// bake steps only between frames.
uint32_t EditorApp::engineFrameLimit() const {
  const bool alone = bake_ || frameCapturePath_ || captureRequested_ || renderDocPending_ || session_->hasCapture() ||
                     std::any_of(inFlight_.begin(), inFlight_.end(), [](const FrameAsks& a) { return a.capture || a.snapshot; });
  return alone ? 1u : session_->framesInFlight();
}

void EditorApp::startEngineFrame() {
  if (!engineActive()) return;
  const uint32_t limit = engineFrameLimit();
  if (inFlight_.size() >= limit || session_->framesInFlightNow() >= limit) return;
  const bool capture = session_->hasCapture();
  const uint32_t w = std::max(1u, uint32_t(viewportSize_.x * settings_.renderScale));
  const uint32_t h = std::max(1u, uint32_t(viewportSize_.y * settings_.renderScale));
  FrameAsks asks;
  asks.begunAt = glfwGetTime();
  try {
    if (capture) frameCapturePath_.reset();  // a reopened capture has no live frame
    if (!capture && (w != session_->settings().width || h != session_->settings().height)) session_->setSize(w, h);
    if (!capture) session_->setView(camera_.view());
    VkFormat hoverFormat = VK_FORMAT_UNDEFINED;
    std::string decoder;
    VkFormat viewedFormat = VK_FORMAT_UNDEFINED;
    uint64_t texels = 0;
    viewer_.aspect = 1.0f;
    for (const auto& r : session_->resources()) {
      if (r.name == preview_) hoverFormat = r.desc.format;
      if (r.name == viewer_.resource)
        decoder = r.desc.decoder, viewedFormat = r.desc.format,
        texels = uint64_t(r.desc.extent.width) * r.desc.extent.height * r.desc.extent.depth,
        viewer_.aspect = viewerAspect(r.desc.extent.width, r.desc.extent.height, viewportSize_);
    }
    // Live read-back of big volumes (the voxel clipmap) would cost more than the frame.
    const bool liveReadback = showBuffers_ && viewer_.live && texels <= (uint64_t(1) << 22);
    lighting::DisplayRequest display =
        displayRequest(viewer_, preview_, hoverFormat, std::exp2(-session_->exposureEv()), decoder, viewedFormat);
    display.selectedInstance = selected_ ? *selected_ + 1 : 0;
    session_->setDisplay(display);
    // The viewer's read-back (histogram, probe, range fit): the shown resource and what its
    // decoder needs beside it.
    if (preview_.empty() && !viewer_.resource.empty() &&
        (viewer_.autoFitPending || viewer_.refresh || viewer_.keepCopy || liveReadback)) {
      session_->requestBuffer(viewer_.resource);
      for (const std::string& c : lighting::decoderCompanions(decoder)) session_->requestBuffer(c);
      asks.viewerReads = true;
      asks.viewed = viewer_.resource;
      asks.keepCopy = viewer_.keepCopy;
    }
    viewer_.refresh = viewer_.keepCopy = false;
    if (!capture) {
      try {
        session_->setCompareView(compareView_);
      } catch (const session::SessionError& e) {
        compareView_.reset();
        session_->setCompareView(std::nullopt);
        showError(e.what());
      }
    }
    session_->requestBuffer(lighting::kDisplayLdr);  // what the window shows
    if (!capture) session_->requestBuffer("gbuffer.instanceId");  // what a click picks
    asks.snapshot = captureRequested_;
    captureRequested_ = false;
    if (frameCapturePath_) {
      session_->requestAllBuffers();
      asks.capture = *frameCapturePath_;
      frameCapturePath_.reset();
      captureInFlight_ = true;
    }
    auto& renderdoc = gpu::RenderDoc::get();
    if (renderDocPending_ && renderdoc.attached()) {
      // RenderDoc brackets the engine's frame on its own device (the window's frames hold only
      // the interface); this one frame waits for the GPU.
      renderDocPending_ = false;
      renderdoc.startFrame(session_->device().instance());
      session_->beginFrame();
      session_->finishFrame();
      notify(renderdoc.endFrame(session_->device().instance()) ? "RenderDoc captured the engine frame"
                                                                : "RenderDoc captured nothing");
    } else {
      session_->beginFrame();
    }
    inFlight_.push_back(asks);
    ++engineFramesBegun_;
    // A resource the frame does not make (the path changed, a capture lacks it): the final
    // image shows, quietly, and the viewer follows.
    const std::string& missing = session_->displayMissing();
    if (!missing.empty() && missing == viewer_.resource) {
      notify(capture ? fmt::format("the capture holds no `{}`: showing its final image", missing)
                     : fmt::format("the {} path does not make `{}`: showing the final image", session_->path(), missing));
      pinPreview("");
    }
    if (!missing.empty() && missing == preview_) preview_.clear();
  } catch (const std::exception& e) {
    showError(e.what());
    preview_.clear();
    viewer_.resource.clear();
    viewer_.showCopy = false;
    pendingClick_.reset();
    captureInFlight_ = false;
  }
}

// Every finished frame is collected, oldest first (a session that settled its frames for a
// change of size or path has finished them all).
void EditorApp::collectEngineFrame() {
  while (!inFlight_.empty() && session_->frameDone()) collectOneEngineFrame();
}

void EditorApp::collectOneEngineFrame() {
  const FrameAsks asks = inFlight_.front();
  inFlight_.pop_front();
  if (asks.capture) captureInFlight_ = false;
  try {
    session_->finishFrame();
  } catch (const std::exception& e) {
    showError(e.what());
    return;
  }
  const double now = glfwGetTime();
  ++engineFramesDone_;
  engineFrameEnds_.push_back(now);
  while (engineFrameEnds_.size() > 2 && now - engineFrameEnds_.front() > 2.0) engineFrameEnds_.pop_front();

  if (const graph::Readback* shown = session_->displayReadback()) {
    // An image equal to the one shown (a still, converged frame) changes nothing on screen.
    if (shown->bytes != shownImage_) shownImage_ = shown->bytes, newImage_ = *shown, imageShown_ = true;
    shownBegunAt_ = asks.begunAt;
    if (asks.snapshot) capture_ = shown->texels();
  } else if (asks.snapshot) {
    captureRequested_ = true;  // the next frame, then
  }
  const bool capture = session_->hasCapture();
  if (!capture && session_->hasBuffer("gbuffer.instanceId")) {
    const graph::Readback& ids = session_->buffer("gbuffer.instanceId");
    pickIds_ = ids.bytes, pickExtent_ = ids.extent;
  }
  if (pendingClick_ && !capture && pickExtent_.width > 0) {
    const glm::vec2 uv = (*pendingClick_ - viewportMin_) / viewportSize_;
    const uint32_t x = std::min(uint32_t(uv.x * float(pickExtent_.width)), pickExtent_.width - 1);
    const uint32_t y = std::min(uint32_t(uv.y * float(pickExtent_.height)), pickExtent_.height - 1);
    uint32_t id = 0;
    std::memcpy(&id, &pickIds_[(size_t(y) * pickExtent_.width + x) * 4], 4);
    select(id == 0 || id > session_->scene().instances.size() ? std::nullopt : std::optional<uint32_t>(id - 1));
    pendingClick_.reset();
  } else if (capture) {
    pendingClick_.reset();
  }
  if (asks.capture) {
    try {
      auto manifest = session::writeCapture(*session_, *asks.capture);
      size_t files = 0;
      for (const auto& r : manifest["resources"]) files += !r["file"].is_null();
      const std::string text = fmt::format("captured {} of {} resources into {}", files, manifest["resources"].size(),
                                           asks.capture->string());
      fmt::print("{}\n", text);
      notify(text);
    } catch (const std::exception& e) {
      showError(fmt::format("capture failed: {}", e.what()));
    }
  }
  // The viewer's read-back, unless it shows another resource since the frame began.
  if (asks.viewerReads && asks.viewed == viewer_.resource && session_->hasBuffer(asks.viewed)) {
    std::string decoder;
    for (const auto& r : session_->resources())
      if (r.name == asks.viewed) decoder = r.desc.decoder;
    viewer_.readbacks.clear();
    viewer_.readbacks[asks.viewed] = session_->buffer(asks.viewed);
    for (const std::string& c : lighting::decoderCompanions(decoder))
      if (session_->hasBuffer(c)) viewer_.readbacks[c] = session_->buffer(c);
    const graph::Readback& shown = viewer_.readbacks[asks.viewed];
    // A meaning is fitted on what it shows (hit distances, irradiance), a fixed one not at all.
    const auto meaning = shownMeaning(viewer_, decoder);
    viewer_.meaningValues = meaning ? lighting::meaningValues(decoder, shown,
                                                              [&](const std::string& c) -> const graph::Readback* {
                                                                auto it = viewer_.readbacks.find(c);
                                                                return it == viewer_.readbacks.end() ? nullptr : &it->second;
                                                              })
                                    : std::vector<float>{};
    if (viewer_.autoFitPending && shown.extent.width > 0) {
      // A frame with nothing in it yet (all zero: an accumulation's first frame, the albedo
      // impact before any edit) fits nothing: the range waits for one with data.
      const auto values = meaning ? viewer_.meaningValues : channelValues(shown, viewer_.channel, viewer_.slice);
      if (meaning && !meaning->fitted) {
        viewer_.autoFitPending = false;
      } else if (auto range = fitRange(values)) {
        std::tie(viewer_.rangeMin, viewer_.rangeMax) = *range;
        viewer_.autoFitPending = false;
      }
    }
    if (asks.keepCopy) viewer_.copyOf = asks.viewed, viewer_.copyReadback = shown;
  }
}

}  // namespace tl::editor
