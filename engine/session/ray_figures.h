// The ray figures for `twinlight bench --rays`. The RT path's: the rays it really traced (pixels
// its pre-trace left pending) against the same rays through a trivial kernel, measured in the
// same frames. The reference's: its paths per second against the rays per second of a trivial
// kernel (reference/raw.rgen) on its own top level, in the same frames. Here, not in the editor, so the editor reaches the RT path's internals only through
// the session.
#pragma once

#include "session/session.h"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace tl::session {

using PassTimes = std::vector<std::pair<std::string, std::vector<double>>>;

// The buffers the figures read from the last frame: request them before it renders.
void requestRayFigureBuffers(Session& session);
// Turns the raw-ray probe on (rtRawRayProbe, referenceRawRayProbe); throws SessionError unless
// the path is `rt` or `reference`.
void enableRayProbe(Session& session);
// From the last frame's pre-trace records and depth and the passes' median times.
nlohmann::json rayFigures(Session& session, const PassTimes& passes);

}  // namespace tl::session
