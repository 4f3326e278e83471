// What `twinlight compare` prints: one view's figures as tables, a sweep's means, and the exit
// status of its regression gate.
#pragma once

#include "session/compare.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace tl::editor {

// One view's figures as tables, and its gate. `failAbove` gives the thresholds' order as the
// user wrote them (a merged report has them only as a JSON object).
void printCompareReport(const nlohmann::json& report, const std::vector<session::GateThreshold>& failAbove);
// A sweep's configurations: their means over the views.
void printSweepReport(const nlohmann::json& report);
// A failed gate is its own exit code (3), after every report is written.
int gateExit(size_t failures, size_t withinNoise = 0);

}  // namespace tl::editor
