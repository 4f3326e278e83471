// `twinlight doctor SCENE`: a stability report. Every available lighting path renders the
// scene for a few frames; the last frame's buffers are all read back and counted
// (session/buffer_health.h: NaN/Inf, negative radiance, invalid SH colours), the mean
// radiance of its image is compared with the reference path's (energy), a short orbit of the
// camera measures how much the image's mean jumps from frame to frame (flicker), the view then
// held measures how many frames the reflections (the specular lobe, composite.specular) take to
// settle after the move (ghosting), and the validation layers' messages during the path's
// frames are counted. Healthy means: no
// non-finite or negative value anywhere and no validation message. Energy and flicker are
// reported, not judged (a real-time path leaves light out by design).
#pragma once

#include "session/buffer_health.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tl::session {

struct DoctorOptions {
  uint32_t frames = 8;          // per real-time path before the buffers are read
  uint32_t referenceSpp = 64;   // the reference's samples per pixel (16 a frame)
  uint32_t orbitFrames = 8;     // frames of the camera orbit that measures flicker
  double orbitDegrees = 0.25;   // the orbit's step per frame, about the point looked at
  uint32_t settleFrames = 16;   // frames the view is held after the orbit to see the reflections settle (0: none;
                                // only after an orbit of 2 frames or more)
};

// How a sequence of frames of one image settles (the reflections after a camera move): the
// settled image is the mean of the last kSettleTail frames; a frame's residual is its L1
// distance to it over the settled image's L1 norm; the noise floor is the largest residual of
// each of those last frames against the mean of the others (leaving it out: a mean holding
// the frame would understate its noise). The lag is the number of frames up to the last one
// before the tail whose residual is above twice the floor plus kSettleMargin: how long what
// the move left behind stays visible above the noise. A lag of every frame before the tail is
// "not settled within the hold".
inline constexpr size_t kSettleTail = 4;
inline constexpr double kSettleMargin = 0.01;
struct SettleFigure {
  uint32_t lag = 0;
  bool settled = true;         // false: still above the noise just before the tail
  double firstResidual = 0.0;  // the first held frame's
  double noiseFloor = 0.0;
};
// `frames`: each frame's values (luminance per pixel, the same count each); at least
// kSettleTail + 1 frames, else nothing.
std::optional<SettleFigure> settleFigure(const std::vector<std::vector<double>>& frames);

struct DoctorPath {
  std::string path;
  std::vector<BufferHealth> buffers;  // every float buffer of the last frame
  uint64_t nonFinite = 0, negative = 0;
  double meanLuminance = 0.0;         // of composite.hdr, static camera, last frame
  std::optional<double> energyRatio;  // meanLuminance / the reference's
  std::optional<double> flicker;      // RMS of the frame-to-frame relative change of the mean over the orbit
  std::optional<SettleFigure> reflectionsSettle;  // the specular lobe, the view held after the orbit
  uint32_t validationMessages = 0;    // during this path's frames
  bool healthy() const { return nonFinite == 0 && negative == 0 && validationMessages == 0; }
};

struct DoctorReport {
  std::string scene;
  uint32_t width = 0, height = 0;
  std::vector<DoctorPath> paths;
  bool healthy() const;
  nlohmann::json toJson() const;
  std::string toText() const;  // a table, then every unhealthy buffer by name
};

// Runs on the session's scene, view, light and size; leaves the session on its path, view
// and settings as it found them.
DoctorReport runDoctor(Session& session, const DoctorOptions& options);

}  // namespace tl::session
