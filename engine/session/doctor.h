// `twinlight doctor SCENE`: a stability report. Every available lighting path renders the
// scene for a few frames; the last frame's buffers are all read back and counted
// (session/buffer_health.h: NaN/Inf, negative radiance, invalid SH colours), the mean
// radiance of its image is compared with the reference path's (energy), a short orbit of the
// camera measures how much the image's mean jumps from frame to frame (flicker), and the
// validation layers' messages during the path's frames are counted. Healthy means: no
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
};

struct DoctorPath {
  std::string path;
  std::vector<BufferHealth> buffers;  // every float buffer of the last frame
  uint64_t nonFinite = 0, negative = 0;
  double meanLuminance = 0.0;         // of composite.hdr, static camera, last frame
  std::optional<double> energyRatio;  // meanLuminance / the reference's
  std::optional<double> flicker;      // RMS of the frame-to-frame relative change of the mean over the orbit
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
