#include "session/ray_figures.h"

#include "metrics/statistics.h"

#include <fmt/format.h>

namespace tl::session {

void requestRayFigureBuffers(Session& session) {
  for (const std::string& name : session.currentPath().rayProbeReadbacks()) session.requestBuffer(name);
}

void enableRayProbe(Session& session) {
  if (!session.currentPath().enableRayProbe(session.settings()))
    throw SessionError(fmt::format("--rays measures a path with a benchmark kernel (rt, reference); `{}` has none",
                                   session.path()));
}

nlohmann::json rayFigures(Session& session, const PassTimes& passes) {
  const lighting::RayProbeFrame frame{
      session.settings(), uint32_t(session.frameIndex() - 1),  // the last frame rendered
      [&](std::string_view name) -> const graph::Readback& { return session.buffer(name); },
      [&](std::string_view pass) {
        for (const auto& [name, ms] : passes)
          if (name == pass) return metrics::median(ms);
        return 0.0;
      }};
  nlohmann::json figures = nlohmann::json::object();
  for (const auto& [name, value] : session.currentPath().rayFigures(frame)) figures[name] = value;
  return figures;
}

}  // namespace tl::session
