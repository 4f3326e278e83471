// The RT path's ray figures for `twinlight bench --rays`: the rays it really traced (pixels its
// pre-trace left pending) against the same rays through a trivial kernel, measured in the same
// frames. Here, not in the editor, so the editor reaches the RT path's internals only through
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
// Turns the raw-ray probe on (rtRawRayProbe); throws SessionError unless the path is `rt`.
void enableRayProbe(Session& session);
// From the last frame's pre-trace records and depth and the passes' median times.
nlohmann::json rayFigures(Session& session, const PassTimes& passes);

}  // namespace tl::session
