#include "session/reference_noise.h"

#include "session/session.h"
#include "shared/reference.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstring>

namespace tl::session {

std::optional<ReferenceNoise> Session::referenceNoise() const {
  const lighting::LightingPath* reference = findPath(referencePath());
  const std::string totals = reference ? reference->capabilities().readouts.noiseTotals : std::string();
  if (capture_ || totals.empty() || !hasBuffer(totals)) return std::nullopt;
  const graph::Readback& rb = buffer(totals);
  shared::RefNoiseTotals t{};
  if (rb.bytes.size() < sizeof(t)) return std::nullopt;
  std::memcpy(&t, rb.bytes.data(), sizeof(t));
  const float rse = shared::tlRefRelativeStdError(t);
  if (!(rse >= 0.0f)) return std::nullopt;
  const double values = 3.0 * double(t.counts.x);
  ReferenceNoise n;
  n.relativeStdError = rse;
  n.meanVariance = double(t.sums.x) / values;
  n.meanValue = double(t.sums.y) / values;
  n.fewestSamples = t.counts.z;
  n.mostSamples = t.counts.w;
  n.meanSamples = double(t.sums.z) / double(t.counts.x);
  return n;
}

ReferenceConvergence Session::renderReferenceUntilNoise(const NoiseTarget& target,
                                                        const std::function<void(const ReferenceConvergence&)>& beforeFrame) {
  if (!(target.relativeStdError > 0.0) || !std::isfinite(target.relativeStdError))
    throw SessionError(fmt::format("the reference's noise target must be a number > 0, not {}", target.relativeStdError));
  if (target.maxSamples == 0 || target.samplesPerFrame == 0)
    throw SessionError("the reference's sample cap and samples per frame must be at least 1");
  const std::string reference = referencePath();
  if (reference.empty()) throw SessionError("this build has no reference path");
  setPath(reference);
  settings_.referenceSamplesPerFrame = target.samplesPerFrame;
  ReferenceConvergence run;
  const auto start = std::chrono::steady_clock::now();
  // One frame at a time: each one's noise is read back (32 bytes) and decides whether another
  // follows, so the render stops at the first frame that meets the target.
  for (;;) {
    if (beforeFrame) beforeFrame(run);
    renderFrames(1);
    ++run.frames;
    run.noise = referenceNoise();
    run.reached = run.noise && run.noise->relativeStdError <= target.relativeStdError;
    // Each frame draws samplesPerFrame a pixel on average, however adaptive sampling spreads them.
    const uint32_t spent = run.frames * target.samplesPerFrame;
    if (run.reached || spent + target.samplesPerFrame > target.maxSamples) break;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace tl::session
