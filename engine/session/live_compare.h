// The Compare panel's engine side, without any UI: two lighting paths and the reference
// render in turn, one per frame, on the same camera; each keeps its last image
// (compare.<path>) for the compare view, and every side's image is measured against the
// reference's latest one when both frames' keys agree on what the reference depends on
// (camera, projection, light, scene, geometry). The reference accumulates while nothing
// changes, so the figures sharpen as it converges; its restarts are counted with their cause.
#pragma once

#include "lighting/common/compare_view_pass.h"
#include "lighting/common/frame_key.h"
#include "graph/executor.h"
#include "metrics/image.h"
#include "metrics/noisy_reference.h"

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
  // The same figures against the converged reference: the reference's noise (its
  // reference.stderr) taken out, with a 95% interval (metrics/noisy_reference.h). Empty until the
  // reference's standard error has come with its image.
  std::optional<metrics::NoiseAwareFigure> relMseAgainstConverged, flipAgainstConverged;
};

// What the panel may say about the two sides: nothing yet, that they are within the noise of
// the reference (their relMSE intervals overlap), or which is closer (the intervals part).
enum class LiveVerdict { None, WithinNoise, LeftCloser, RightCloser };

class LiveCompare {
 public:
  // `reference`: the path the sides are measured against (PathCapabilities::isReference);
  // `referenceReason`: why it cannot run here (no ray tracing); then the sides still alternate
  // but no error is measured.
  LiveCompare(CompareView view, std::string reference, std::optional<std::string> referenceReason);
  ~LiveCompare();  // waits for a FLIP measurement under way

  const CompareView& view() const { return view_; }
  // Changing the sides keeps what was rendered (each path's image stays until replaced).
  void setView(const CompareView& view) { view_ = view; }
  const std::optional<std::string>& referenceUnavailable() const { return referenceReason_; }
  const std::string& referencePath() const { return reference_; }

  // The path the next frame renders: left, right and the reference in turn.
  std::string nextPath();
  // How many paths take turns (each renders every rotationLength()-th frame).
  size_t rotationLength() const { return rotation().size(); }
  // Whether compare.<path> holds an image yet.
  bool hasImage(const std::string& path) const { return images_.count(path) != 0; }
  // After a frame of `path`: its image (compare.<path>), its GPU time, its frame key and, for
  // the reference, its samples, what its accumulation did in that frame and its standard error
  // (reference.stderr: null when the frame did not read it back).
  void frameDone(const std::string& path, const graph::Readback& image, double gpuMs, const lighting::FrameKey& key,
                 uint32_t referenceSamples, float exposure,
                 const std::optional<lighting::HistoryDecision>& referenceAccumulation = std::nullopt,
                 const graph::Readback* referenceStdErr = nullptr);

  // Left and right, in that order (one entry when both sides show the same path).
  std::vector<LiveError> errors() const;
  // Waits for the FLIP measurements under way and takes their figures (tests, scripts).
  void finishFlip();
  // Whether a FLIP measurement's worker is still running (the editor waits for it, bounded,
  // before the scene it measures goes).
  bool measuring() const;
  uint32_t referenceSamples() const { return referenceSamples_; }
  // How often the reference's accumulation started over while a sum was under way, and the
  // frame-key parts that made it do so the last time (e.g. camera.position; none when its
  // history was lost to a resize or a reset).
  uint32_t referenceRestarts() const { return referenceRestarts_; }
  lighting::FrameParts lastReferenceRestart() const { return lastRestart_; }

  // The reference's own error: its relMSE against the converged image at the samples it holds
  // now, estimated from two of its states in one accumulation (see updateNoise); none until
  // it has doubled its samples once. A side's relMSE against a noisy reference carries about
  // this much of the reference's noise besides its own error.
  std::optional<double> referenceNoise() const;
  // Whether the reference is converged enough to rank the sides: with its standard error, when
  // the sides' relMSE intervals against the converged reference part (verdict()); without it,
  // when its noise is at most 1/kTrustRatio of the gap between their relMSE (of its relMSE, when
  // one side is compared).
  static constexpr double kTrustRatio = 4.0;
  bool referenceTrusted() const;
  // The verdict on the two sides (None while either lacks a figure against the converged
  // reference, while the reference has fewer than kMinVerdictSamples samples, or when one side
  // is the reference itself). Below that count the per-pixel standard error misses the rare,
  // bright paths a pixel has not drawn yet (at 1 sample it is 0), so its intervals would be too
  // narrow: 16 samples give each pixel's variance 15 degrees of freedom.
  static constexpr uint32_t kMinVerdictSamples = 16;
  LiveVerdict verdict() const;

  // The parts of the frame key a side's image and the reference's must share to be compared.
  static constexpr lighting::FrameParts kComparedParts =
      lighting::kCameraParts | lighting::parts(lighting::FramePart::Sun, lighting::FramePart::Sky,
                                               lighting::FramePart::Scene, lighting::FramePart::Geometry);

 private:
  std::vector<std::string> rotation() const;
  void measure(const std::string& path, float exposure);

  struct Side {
    metrics::Image image;
    lighting::FrameKey key;
    double gpuMs = 0.0;
    metrics::Image variance;  // the reference's: its standard error squared (empty: not known)
  };
  CompareView view_;
  std::string reference_;
  std::optional<std::string> referenceReason_;
  size_t turn_ = 0;
  std::map<std::string, Side> images_;
  std::map<std::string, LiveError> errors_;
  std::map<std::string, std::chrono::steady_clock::time_point> lastFlip_;
  // FLIP under way per path, with the frame key of the images it measures: a result arrives only
  // while both images still show that view.
  struct PendingFlip {
    std::future<metrics::NoiseAwareFigure> value;
    lighting::FrameKey key;
  };
  std::map<std::string, PendingFlip> pendingFlip_;
  void collectFlip(bool wait);
  void updateNoise(const Side& reference, uint32_t samples);
  // The reference at an earlier sample count of the same accumulation, and the last estimate.
  struct Checkpoint {
    metrics::Image image;
    lighting::FrameKey key;
    uint32_t samples = 0;
  };
  std::optional<Checkpoint> checkpoint_;
  std::optional<double> noise_;  // at noiseSamples_
  uint32_t noiseSamples_ = 0;
  uint32_t referenceSamples_ = 0;
  bool referenceSeen_ = false;
  uint32_t referenceRestarts_ = 0;
  lighting::FrameParts lastRestart_ = 0;
};

}  // namespace tl::session
