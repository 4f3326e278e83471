// The ray figures for `twinlight bench --rays`, which the path makes itself
// (LightingPath::rayFigures): the RT path's rays really traced against the same rays through a
// trivial kernel, the reference's paths per second against a trivial kernel's rays per second on
// its own top level, each measured in the same frames.
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
// Turns the path's trivial kernel on (rtRawRayProbe, referenceRawRayProbe); throws SessionError
// for a path that has none.
void enableRayProbe(Session& session);
// From the last frame's read-backs and the passes' median times.
nlohmann::json rayFigures(Session& session, const PassTimes& passes);

}  // namespace tl::session
