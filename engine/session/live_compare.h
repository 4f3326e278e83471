// The Compare panel's engine side, without any UI: two lighting paths and the reference
// render in turn, one per frame, on the same camera; each keeps its last image
// (compare.<path>) for the compare view, and every side's image is measured against the
// reference's latest one when both show the same view, light and size. The reference
// accumulates while nothing changes, so the figures sharpen as it converges.
#pragma once

#include "lighting/common/compare_view_pass.h"
#include "graph/executor.h"
#include "metrics/image.h"

#include <chrono>
#include <future>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tl::session {

struct CompareView : lighting::CompareViewRequest {
  // LDR-FLIP on the CPU as well as relMSE, started at most every flipInterval on a worker
  // thread: the figure shown is the last one finished, frames never wait for it.
  bool measureFlip = true;
  double flipIntervalSeconds = 1.5;
};

// One side's error against the reference, from the last images that shared a view.
struct LiveError {
  std::string path;
  double gpuMs = 0.0;               // the side's last frame
  std::optional<double> relMse;     // linear radiance, same epsilon as `compare`
  std::optional<double> flip;       // LDR-FLIP of the display images (same exposure)
  uint32_t referenceSamples = 0;    // what the reference had accumulated when measured
};

class LiveCompare {
 public:
  // `referenceReason`: why the reference cannot run here (no ray tracing); then the sides
  // still alternate but no error is measured.
  LiveCompare(CompareView view, std::optional<std::string> referenceReason);
  ~LiveCompare();  // waits for a FLIP measurement under way

  const CompareView& view() const { return view_; }
  // Changing the sides keeps what was rendered (each path's image stays until replaced).
  void setView(const CompareView& view) { view_ = view; }
  const std::optional<std::string>& referenceUnavailable() const { return referenceReason_; }

  // The path the next frame renders: left, right and the reference in turn.
  std::string nextPath();
  // How many paths take turns (each renders every rotationLength()-th frame).
  size_t rotationLength() const { return rotation().size(); }
  // Whether compare.<path> holds an image yet.
  bool hasImage(const std::string& path) const { return images_.count(path) != 0; }
  // After a frame of `path`: its image (compare.<path>), its GPU time, a stamp of everything
  // the reference depends on (view, light, size, scene) and, for the reference, its samples.
  void frameDone(const std::string& path, const graph::Readback& image, double gpuMs, uint64_t stamp,
                 uint32_t referenceSamples, float exposure);

  // Left and right, in that order (one entry when both sides show the same path).
  std::vector<LiveError> errors() const;
  // Waits for the FLIP measurements under way and takes their figures (tests, scripts).
  void finishFlip();
  uint32_t referenceSamples() const { return referenceSamples_; }

 private:
  std::vector<std::string> rotation() const;
  void measure(const std::string& path, float exposure);

  struct Side {
    metrics::Image image;
    uint64_t stamp = 0;
    double gpuMs = 0.0;
  };
  CompareView view_;
  std::optional<std::string> referenceReason_;
  size_t turn_ = 0;
  std::map<std::string, Side> images_;
  std::map<std::string, LiveError> errors_;
  std::map<std::string, std::chrono::steady_clock::time_point> lastFlip_;
  // FLIP under way per path, with the stamp of the images it measures: a result arrives only
  // while both images still show that view.
  struct PendingFlip {
    std::future<double> value;
    uint64_t stamp = 0;
  };
  std::map<std::string, PendingFlip> pendingFlip_;
  void collectFlip(bool wait);
  uint32_t referenceSamples_ = 0;
};

}  // namespace tl::session
