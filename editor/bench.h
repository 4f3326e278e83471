// `twinlight bench`: per-pass GPU milliseconds (median and spread over N frames after a
// warm-up that compiles the pipelines) as a table and as JSON. A benchmark, not a test:
// the figures are reported, never asserted.
#pragma once

#include "session/session.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

struct BenchOptions {
  uint32_t frames = 20;
  uint32_t warmup = 2;
  bool rays = false;  // rt path: raw ray throughput on the scene's TLAS against the path's traced rays/s
  bool cutEveryFrame = false;  // every measured frame starts without history: a camera cut's cost
  uint32_t framesInFlight = 2;  // 1: the host waits for each frame before recording the next
  // The wall-clock time per frame with one frame in flight against framesInFlight, measured
  // in turns in the same run: what recording a frame while the device runs the one before
  // gains on this device.
  bool againstOneInFlight = false;
};

// `progress` (optional): what is being done and the fraction of the frames rendered.
nlohmann::json runBench(tl::session::Session& session, const BenchOptions& options,
                        const std::function<void(const std::string& what, double fraction)>& progress = {});
std::string benchTable(const nlohmann::json& report);
