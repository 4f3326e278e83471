#include "session/live_compare.h"

#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "session/compare.h"

#include <algorithm>
#include <cmath>

namespace tl::session {

LiveCompare::LiveCompare(CompareView view, std::string reference, std::optional<std::string> referenceReason)
    : view_(std::move(view)), reference_(std::move(reference)), referenceReason_(std::move(referenceReason)) {}

std::vector<std::string> LiveCompare::rotation() const {
  std::vector<std::string> order{view_.left};
  if (view_.right != view_.left) order.push_back(view_.right);
  if (!referenceReason_ && view_.left != reference_ && view_.right != reference_) order.push_back(reference_);
  return order;
}

std::string LiveCompare::nextPath() {
  const auto order = rotation();
  return order[turn_++ % order.size()];
}

namespace {
// Whether two frames agree on everything a compared image depends on (see kComparedParts).
bool sameCompared(const lighting::FrameKey& a, const lighting::FrameKey& b) {
  return (lighting::differingParts(a, b) & LiveCompare::kComparedParts) == 0;
}
}  // namespace

LiveCompare::~LiveCompare() { collectFlip(true); }

void LiveCompare::collectFlip(bool wait) {
  for (auto it = pendingFlip_.begin(); it != pendingFlip_.end();) {
    auto& [path, pending] = *it;
    if (!wait && pending.value.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      ++it;
      continue;
    }
    const metrics::NoiseAwareFigure value = pending.value.get();
    auto side = images_.find(path), ref = images_.find(reference_);
    if (side != images_.end() && ref != images_.end() && sameCompared(side->second.key, pending.key) &&
        sameCompared(ref->second.key, pending.key) && view_.measureFlip) {
      errors_[path].flip = value.raw;
      if (value.high > value.low) errors_[path].flipAgainstConverged = value;
    }
    it = pendingFlip_.erase(it);
  }
}

void LiveCompare::finishFlip() { collectFlip(true); }

void LiveCompare::frameDone(const std::string& path, const graph::Readback& image, double gpuMs,
                            const lighting::FrameKey& key, uint32_t referenceSamples, float exposure,
                            const std::optional<lighting::HistoryDecision>& referenceAccumulation,
                            const graph::Readback* referenceStdErr) {
  collectFlip(false);
  Side& side = images_[path];
  side.image = rgbImage(image);
  side.key = key;
  side.gpuMs = gpuMs;
  side.variance = {};
  if (referenceStdErr && referenceStdErr->extent.width == side.image.width && referenceStdErr->extent.height == side.image.height) {
    side.variance = rgbImage(*referenceStdErr);
    for (float& v : side.variance.data) v *= v;
  }
  errors_[path].path = path;
  errors_[path].gpuMs = gpuMs;
  if (path == reference_) {
    // Only a sum this compare saw under way restarts; its first frame starts one.
    if (referenceSeen_ && referenceAccumulation && referenceAccumulation->action == lighting::HistoryAction::Restart)
      ++referenceRestarts_, lastRestart_ = referenceAccumulation->acted;
    referenceSeen_ = true;
    referenceSamples_ = referenceSamples;
    updateNoise(side, referenceSamples);
    // A converging reference improves every side's figure: re-measure both.
    for (const std::string& p : {view_.left, view_.right})
      if (p != reference_) measure(p, exposure);
  } else {
    measure(path, exposure);
  }
}

void LiveCompare::measure(const std::string& path, float exposure) {
  auto side = images_.find(path), ref = images_.find(reference_);
  LiveError& e = errors_[path];
  e.path = path;
  if (side == images_.end() || ref == images_.end() ||
      !sameCompared(side->second.key, ref->second.key) ||
      side->second.image.width != ref->second.image.width || side->second.image.height != ref->second.image.height) {
    e.relMse.reset(), e.flip.reset();  // no reference of this view yet: no figure rather than a wrong one
    return;
  }
  e.relMse = metrics::relMse(side->second.image, ref->second.image).value;
  e.relMseAgainstConverged.reset();
  if (!ref->second.variance.data.empty())
    e.relMseAgainstConverged = metrics::relMseNoiseAware(side->second.image, ref->second.image, ref->second.variance);
  e.referenceSamples = referenceSamples_;
  auto now = std::chrono::steady_clock::now();
  auto last = lastFlip_.find(path);
  // The interval only spaces out refreshes: a side whose figure was dropped (the view changed) is due
  // at once, or on a fast device it would show no FLIP for a whole interval after every camera step.
  const bool due = !e.flip || last == lastFlip_.end() ||
                   std::chrono::duration<double>(now - last->second).count() >= view_.flipIntervalSeconds;
  if (view_.measureFlip && due && !pendingFlip_.count(path)) {
    // The worker gets its own copies: the sides' images change under it on the next frames.
    // Against the converged reference by simulation-extrapolation when its noise is known
    // (metrics/noisy_reference.h): five FLIPs, on the worker.
    auto job = [test = displayEncode(side->second.image, exposure), reference = ref->second.image,
                variance = ref->second.variance, exposure] {
      return metrics::simexNoiseAware(reference, variance, [&](const metrics::Image& r) {
        return metrics::flipLdr(test, displayEncode(r, exposure)).value;
      });
    };
    pendingFlip_[path] = {std::async(std::launch::async, std::move(job)), side->second.key};
    lastFlip_[path] = now;
  } else if (!view_.measureFlip) {
    e.flip.reset();
  }
}

// The reference at n samples is the mean b of n samples; a checkpoint a of the same sum at
// n1 < n samples holds the first n1 of them. With c the mean of the other n - n1,
// a - b = (n - n1)/n (a - c), whose variance is s2 (n - n1)/(n n1) for a per-sample variance
// s2, while b's own variance (its error against the converged image) is s2/n. So
// noise(b) = E|a - b|^2 n1/(n - n1): relMSE(a, b) scaled, the same relative measure as the
// sides' figures. It is taken each time the sum has doubled (n >= 2 n1: enough new samples
// for a steady estimate) and scales as 1/n in between.
void LiveCompare::updateNoise(const Side& reference, uint32_t samples) {
  const bool sameSum = checkpoint_ && sameCompared(checkpoint_->key, reference.key) && samples >= checkpoint_->samples &&
                       checkpoint_->image.width == reference.image.width &&
                       checkpoint_->image.height == reference.image.height;
  if (!sameSum || checkpoint_->samples == 0) {
    noise_.reset();  // a new sum (or the first): nothing to compare with yet
    checkpoint_ = Checkpoint{reference.image, reference.key, samples};
    return;
  }
  const uint32_t n1 = checkpoint_->samples;
  if (samples < 2 * n1) return;
  noise_ = metrics::relMse(checkpoint_->image, reference.image).value * double(n1) / double(samples - n1);
  noiseSamples_ = samples;
  checkpoint_ = Checkpoint{reference.image, reference.key, samples};
}

std::optional<double> LiveCompare::referenceNoise() const {
  if (!noise_ || referenceSamples_ < noiseSamples_ || referenceSamples_ == 0) return std::nullopt;
  return *noise_ * double(noiseSamples_) / double(referenceSamples_);
}

LiveVerdict LiveCompare::verdict() const {
  const auto e = errors();
  if (e.size() != 2 || e[0].path == reference_ || e[1].path == reference_ || !e[0].relMseAgainstConverged ||
      !e[1].relMseAgainstConverged || e[0].referenceSamples < kMinVerdictSamples ||
      e[1].referenceSamples < kMinVerdictSamples)
    return LiveVerdict::None;
  switch (metrics::rank(*e[0].relMseAgainstConverged, *e[1].relMseAgainstConverged)) {
    case metrics::Ranking::Lower: return LiveVerdict::LeftCloser;
    case metrics::Ranking::Higher: return LiveVerdict::RightCloser;
    default: return LiveVerdict::WithinNoise;
  }
}

bool LiveCompare::referenceTrusted() const {
  const auto e = errors();
  if (!e.empty() && e.front().relMseAgainstConverged) {
    if (e.size() == 2 && e.back().relMseAgainstConverged) {
      const LiveVerdict v = verdict();
      return v == LiveVerdict::LeftCloser || v == LiveVerdict::RightCloser;
    }
    // One side: its interval lies clear of 0 (its error is its own, not the reference's noise).
    return e.front().referenceSamples >= kMinVerdictSamples && e.front().relMseAgainstConverged->low > 0.0;
  }
  const auto noise = referenceNoise();
  if (!noise) return false;
  if (e.empty() || !e.front().relMse) return false;
  const double scale = e.size() == 2 && e.back().relMse ? std::abs(*e.front().relMse - *e.back().relMse) : *e.front().relMse;
  return *noise * kTrustRatio <= scale;
}

bool LiveCompare::measuring() const {
  return std::any_of(pendingFlip_.begin(), pendingFlip_.end(), [](const auto& p) {
    return p.second.value.valid() && p.second.value.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
  });
}

std::vector<LiveError> LiveCompare::errors() const {
  std::vector<LiveError> out;
  for (const std::string& p : {view_.left, view_.right}) {
    if (!out.empty() && out.back().path == p) continue;
    auto it = errors_.find(p);
    out.push_back(it != errors_.end() ? it->second : LiveError{p});
  }
  return out;
}

}  // namespace tl::session
