#include "session/ray_figures.h"

#include "lighting/common/gbuffer_pass.h"
#include "lighting/reference/reference_path.h"
#include "lighting/rt/rt_path.h"
#include "metrics/statistics.h"
#include "shared/rt.h"

#include <algorithm>
#include <cstring>

namespace tl::session {
namespace {

using metrics::median;

double medianOf(const PassTimes& passes, const std::string& pass) {
  for (const auto& [name, ms] : passes)
    if (name == pass) return median(ms);
  return 0.0;
}

}  // namespace

// The reference's paths per second against the raw kernel's rays per second on its top level.
nlohmann::json referenceRayFigures(Session& session, const PassTimes& passes) {
  const auto counts = session.buffer(lighting::kReferenceRawRays).texels();
  double rawRays = 0.0;
  for (float c : counts) rawRays += c;
  const double pixels = double(session.settings().width) * session.settings().height;
  const double paths = pixels * session.settings().referenceSamplesPerFrame;
  const double rawMs = medianOf(passes, "reference.rawRays"), traceMs = medianOf(passes, "reference.trace");
  const double rawRate = rawMs > 0.0 ? rawRays / (rawMs * 1e-3) : 0.0;
  const double pathRate = traceMs > 0.0 ? paths / (traceMs * 1e-3) : 0.0;
  return {{"paths", paths},  // this frame's: samples per frame a pixel (adaptive sampling spreads them)
          {"traceMs", traceMs},
          {"pathsPerSecond", pathRate},
          {"rawRays", rawRays},
          {"rawRaysPerPath", paths > 0.0 ? rawRays / paths : 0.0},
          {"rawKernelMs", rawMs},
          {"rawRaysPerSecond", rawRate},
          // What one path costs, in the trivial kernel's rays: the raw rate over the path rate.
          {"rawRaysPerPathTime", pathRate > 0.0 ? rawRate / pathRate : 0.0}};
}

void requestRayFigureBuffers(Session& session) {
  if (session.path() == "reference") {
    session.requestBuffer(lighting::kReferenceRawRays);
    return;
  }
  session.requestBuffer(lighting::kPretraceHits);
  session.requestBuffer(lighting::gbuffer::kDepth);
}

void enableRayProbe(Session& session) {
  if (session.path() == "reference") {
    session.settings().referenceRawRayProbe = true;
    return;
  }
  if (session.path() != "rt") throw SessionError("--rays measures the rt path or the reference: add --path rt or --path reference");
  session.settings().rtRawRayProbe = true;
}

nlohmann::json rayFigures(Session& session, const PassTimes& passes) {
  if (session.path() == "reference") return referenceRayFigures(session, passes);
  const auto& pre = session.buffer(lighting::kPretraceHits);
  const auto depth = session.buffer(lighting::gbuffer::kDepth).texels();
  std::vector<uint32_t> hits(pre.bytes.size() / 4);
  std::memcpy(hits.data(), pre.bytes.data(), hits.size() * 4);
  size_t surface = 0, pending = 0;
  const uint32_t w = session.settings().width;
  const uint32_t frame = uint32_t(session.frameIndex() - 1);  // the last frame rendered
  const uint32_t pattern = lighting::rtRayPattern(session.settings());
  for (size_t i = 0; i < hits.size() && i < depth.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    if (!shared::tlRtTracesThisFrame(glm::ivec2(int(i % w), int(i / w)), frame, pattern)) continue;
    ++surface;
    pending += shared::tlRtIsPending(hits[i]);
  }
  const double rawMs = medianOf(passes, "rt.rawRays"), traceMs = medianOf(passes, "rt.trace");
  const double rawPendingMs = medianOf(passes, "rt.rawRays.pending");
  const double rawRate = rawMs > 0.0 ? double(surface) / (rawMs * 1e-3) : 0.0;
  const double rawPendingRate = rawPendingMs > 0.0 ? double(pending) / (rawPendingMs * 1e-3) : 0.0;
  const double rtRate = traceMs > 0.0 ? double(pending) / (traceMs * 1e-3) : 0.0;
  const double pixels = double(session.settings().width) * session.settings().height;
  return {{"surfacePixels", surface},  // traced this frame (all, this frame's checkerboard or 2x2 pixel)
          {"realRays", pending},
          {"pretraceShare", surface ? 1.0 - double(pending) / double(surface) : 0.0},
          {"realRaysPerPixel", pending / pixels},
          {"rawKernelMs", rawMs},
          {"rawRaysPerSecond", rawRate},
          {"traceMs", traceMs},
          {"rtRaysPerSecond", rtRate},
          {"rtOverRaw", rawRate > 0.0 ? rtRate / rawRate : 0.0},
          // The same trivial kernel on only the rays rt.trace traced: those left after the
          // pre-trace are the long, incoherent ones, slower per ray for any kernel.
          {"rawPendingKernelMs", rawPendingMs},
          {"rawPendingRaysPerSecond", rawPendingRate},
          {"rtOverRawSameRays", rawPendingRate > 0.0 ? rtRate / rawPendingRate : 0.0}};
}


}  // namespace tl::session
