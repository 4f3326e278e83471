#include "session/doctor.h"

#include "lighting/common/composite_pass.h"
#include "shared/common.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace tl::session {
namespace {

// The luminance of every pixel of `image` (non-finite where the pixel is).
std::vector<double> luminanceOf(const graph::Readback& image) {
  const std::vector<float> t = image.texels();
  const uint32_t c = image.channels();
  std::vector<double> y;
  if (c < 3) return y;
  for (size_t i = 0; i + 2 < t.size(); i += c) y.push_back(shared::tlLuminance(glm::vec3(t[i], t[i + 1], t[i + 2])));
  return y;
}

// The mean luminance of the frame's composite.hdr over its finite pixels.
double meanLuminance(const Session& session) {
  double sum = 0.0;
  size_t n = 0;
  for (double y : luminanceOf(session.buffer(lighting::kCompositeHdr)))
    if (std::isfinite(y)) sum += y, ++n;
  return n ? sum / double(n) : 0.0;
}

// The view turned by `degrees` about the vertical axis through the point it looks at (the
// scene's centre distance ahead).
View orbit(const View& v, double distance, double degrees) {
  const glm::dvec3 pivot = v.position + v.forward * distance;
  const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
  View o = v;
  o.position = pivot + glm::dvec3(r * glm::dvec4(v.position - pivot, 0.0));
  o.forward = glm::dvec3(r * glm::dvec4(v.forward, 0.0));
  o.up = glm::dvec3(r * glm::dvec4(v.up, 0.0));
  return o;
}

}  // namespace

std::optional<SettleFigure> settleFigure(const std::vector<std::vector<double>>& frames) {
  if (frames.size() < kSettleTail + 1) return std::nullopt;
  const size_t n = frames.front().size(), first = frames.size() - kSettleTail;
  for (const auto& frame : frames)
    if (frame.size() != n) return std::nullopt;
  std::vector<double> settled(n, 0.0);
  for (size_t f = first; f < frames.size(); ++f)
    for (size_t i = 0; i < n; ++i) settled[i] += frames[f][i] / double(kSettleTail);
  double norm = 0.0;
  for (double v : settled) norm += std::abs(v);
  if (!(norm > 0.0)) return std::nullopt;  // no reflected light to settle
  auto residual = [&](const std::vector<double>& frame) {
    double d = 0.0;
    for (size_t i = 0; i < n; ++i) d += std::abs(frame[i] - settled[i]);
    return d / norm;
  };
  SettleFigure fig;
  for (size_t f = first; f < frames.size(); ++f) {
    double d = 0.0;  // against the mean of the tail's other frames
    for (size_t i = 0; i < n; ++i)
      d += std::abs(frames[f][i] - (settled[i] * double(kSettleTail) - frames[f][i]) / double(kSettleTail - 1));
    fig.noiseFloor = std::max(fig.noiseFloor, d / norm);
  }
  fig.firstResidual = residual(frames.front());
  const double threshold = 2.0 * fig.noiseFloor + kSettleMargin;
  for (size_t f = 0; f < first; ++f)
    if (residual(frames[f]) > threshold) fig.lag = uint32_t(f + 1);
  fig.settled = fig.lag < first;
  return fig;
}

bool DoctorReport::healthy() const {
  for (const auto& p : paths)
    if (!p.healthy()) return false;
  return !paths.empty();
}

nlohmann::json DoctorReport::toJson() const {
  nlohmann::json j = {{"scene", scene}, {"width", width}, {"height", height}, {"healthy", healthy()}};
  j["paths"] = nlohmann::json::array();
  for (const auto& p : paths) {
    nlohmann::json jp = {{"path", p.path},           {"healthy", p.healthy()},
                         {"nonFinite", p.nonFinite}, {"negative", p.negative},
                         {"meanLuminance", p.meanLuminance}, {"validationMessages", p.validationMessages}};
    jp["energyRatio"] = p.energyRatio ? nlohmann::json(*p.energyRatio) : nlohmann::json();
    jp["flicker"] = p.flicker ? nlohmann::json(*p.flicker) : nlohmann::json();
    jp["reflectionsSettle"] = p.reflectionsSettle
                                  ? nlohmann::json{{"frames", p.reflectionsSettle->lag},
                                                   {"settled", p.reflectionsSettle->settled},
                                                   {"firstResidual", p.reflectionsSettle->firstResidual},
                                                   {"noiseFloor", p.reflectionsSettle->noiseFloor}}
                                  : nlohmann::json();
    jp["buffers"] = nlohmann::json::array();
    for (const auto& b : p.buffers)
      jp["buffers"].push_back({{"name", b.name}, {"check", b.check}, {"values", b.values}, {"nonFinite", b.nonFinite},
                               {"negative", b.negative}, {"mostNegative", b.mostNegative}});
    j["paths"].push_back(jp);
  }
  return j;
}

std::string DoctorReport::toText() const {
  std::string s =
      fmt::format("doctor: {} at {}x{}\n{:10} {:>8} {:>10} {:>9} {:>11} {:>9} {:>20} {:>11}\n", scene, width, height,
                  "path", "buffers", "non-finite", "negative", "energy/ref", "flicker", "reflections settle", "layers");
  for (const auto& p : paths) {
    // The frames the reflections took to settle after the move, and how far off the first was.
    // ">=": not settled within the hold.
    const std::string settle =
        p.reflectionsSettle
            ? fmt::format("{}{} frames ({:.0f}%)", p.reflectionsSettle->settled ? "" : ">=", p.reflectionsSettle->lag,
                          100.0 * p.reflectionsSettle->firstResidual)
            : "-";
    s += fmt::format("{:10} {:>8} {:>10} {:>9} {:>11} {:>9} {:>20} {:>11}\n", p.path, p.buffers.size(), p.nonFinite,
                     p.negative, p.energyRatio ? fmt::format("{:.3f}", *p.energyRatio) : "-",
                     p.flicker ? fmt::format("{:.2f}%", 100.0 * *p.flicker) : "-", settle, p.validationMessages);
  }
  bool any = false;
  for (const auto& p : paths)
    for (const auto& b : p.buffers)
      if (!b.healthy()) {
        s += fmt::format("  {} {}: {} non-finite, {} negative of {} ({}; lowest {:g})\n", p.path, b.name, b.nonFinite,
                         b.negative, b.values, b.check, b.mostNegative);
        any = true;
      }
  s += healthy() ? "healthy: every buffer finite, no negative radiance, no message from the Vulkan layers\n"
                 : (any ? "UNHEALTHY\n" : "UNHEALTHY (messages from the Vulkan layers)\n");
  return s;
}

DoctorReport runDoctor(Session& session, const DoctorOptions& o) {
  DoctorReport report;
  report.scene = session.scene().name;
  report.width = session.settings().width;
  report.height = session.settings().height;
  const std::string startPath = session.path();
  const View startView = session.view();
  const lighting::RenderSettings startSettings = session.settings();
  const auto& b = session.scene().bounds;
  const double distance = b.valid() ? std::max(glm::length(b.center() - startView.position), 1e-3) : 1.0;

  // The reference first: the others' energy is measured against it.
  std::vector<std::string> order;
  for (const auto& p : session.paths())
    if (p.available && p.capabilities.isReference) order.push_back(p.name);
  for (const auto& p : session.paths())
    if (p.available && !p.capabilities.isReference) order.push_back(p.name);

  std::optional<double> referenceMean;
  for (const std::string& name : order) {
    DoctorPath r;
    r.path = name;
    const uint32_t validationBefore = session.validationErrors();
    session.setPath(name);
    session.setView(startView);
    session.settings() = startSettings;
    const bool reference = name == session.referencePath();
    if (reference) session.settings().referenceSamplesPerFrame = std::min(o.referenceSpp, 16u);
    const uint32_t frames = reference ? std::max(1u, (o.referenceSpp + 15) / 16) : std::max(1u, o.frames);
    session.resetHistory();
    if (frames > 1) session.renderFrames(frames - 1);
    session.requestAllBuffers();
    session.renderFrames(1);
    r.buffers = bufferHealth(session);
    for (const auto& h : r.buffers) {
      r.nonFinite += h.nonFinite;
      r.negative += h.negative;
    }
    r.meanLuminance = meanLuminance(session);
    if (reference) referenceMean = r.meanLuminance;
    if (referenceMean && *referenceMean > 0.0) r.energyRatio = r.meanLuminance / *referenceMean;
    // Flicker: the real-time paths along a slow orbit, their history carried along.
    if (!reference && o.orbitFrames >= 2) {
      double previous = r.meanLuminance, sum = 0.0;
      uint32_t steps = 0;
      for (uint32_t k = 1; k <= o.orbitFrames; ++k) {
        session.setView(orbit(startView, distance, o.orbitDegrees * double(k)));
        session.renderFrames(1);
        const double mean = meanLuminance(session);
        if (previous > 0.0) {
          sum += (mean / previous - 1.0) * (mean / previous - 1.0);
          ++steps;
        }
        previous = mean;
      }
      if (steps) r.flicker = std::sqrt(sum / double(steps));
      // Ghosting: the view held where the orbit stopped, the specular lobe frame by frame until
      // it has settled (paths through the composite only: the others have no lobe split).
      std::vector<std::vector<double>> held;
      for (uint32_t k = 0; k < o.settleFrames; ++k) {
        session.requestBuffer(lighting::kCompositeSpecularLobe);
        session.renderFrames(1);
        if (!session.hasBuffer(lighting::kCompositeSpecularLobe)) break;
        held.push_back(luminanceOf(session.buffer(lighting::kCompositeSpecularLobe)));
        for (double& y : held.back())
          if (!std::isfinite(y)) y = 0.0;  // the health check counts it; here it would poison the sums
      }
      r.reflectionsSettle = settleFigure(held);
    }
    r.validationMessages = session.validationErrors() - validationBefore;
    report.paths.push_back(std::move(r));
  }
  session.setPath(startPath);
  session.setView(startView);
  session.settings() = startSettings;
  session.resetHistory();
  return report;
}

}  // namespace tl::session
