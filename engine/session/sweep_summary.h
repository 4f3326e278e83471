// One table for a sweep over many views (a corpus of scenes): per view and path, the mean
// ratio and relMSE_norm against the view's reference, and the share of views that meet each
// of the project's accuracy goals:
//   rt mean within +-10% of the reference        (target: 95% of the lit views)
//   rt relMSE_norm at most 0.5x legacy's          (target: 90%)
//   legacy mean within +-35% of the reference    (target: 90%)
//   a dark view stays dark in every path         (target: all of them)
// A view is dark when its reference holds under 1% of the light of the brightest view of the
// same scene (the sealed room beside a lit one): a path passes there when its mean stays under
// 1% of that brightest view's. A scene whose every view is black has no figure to judge and is
// listed apart.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace tl::session {

// From a sweep report (sweep.h: "views", each with its reference and paths): the summary as
// JSON ("views": per view its class and figures; "goals": per goal met / judged / share /
// target / held).
nlohmann::json summarizeSweep(const nlohmann::json& sweepReport);

// The summary as the fixed-width text `compare` prints after a sweep.
std::string sweepSummaryTable(const nlohmann::json& summary);

}  // namespace tl::session
