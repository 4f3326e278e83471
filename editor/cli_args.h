// Parsing and applying the command line's view and light options, and the exit status every
// headless subcommand ends with.
#pragma once

#include "session/session.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

// Ceilings on what one command may ask for, so every loop a user value controls ends
// (docs/user-guide.md, "Input limits, hard cases and `twinlight doctor`"). Frames: render,
// capture, bench and compare; spp: the reference's samples per pixel (16 a frame); a side of the
// image: the Vulkan minimum every device supports for 2D images is 4096, lavapipe's and most
// GPUs' is 16384.
inline constexpr uint32_t kMaxFrames = 100000;
inline constexpr uint32_t kMaxWarmupFrames = 1000;
inline constexpr uint32_t kMaxSpp = 65536;
inline constexpr uint32_t kMaxBounces = 64;
inline constexpr uint64_t kMaxImageSide = 16384;
// Bad usage found after parsing (options that contradict each other, a malformed value that
// CLI11 cannot check): one `twinlight: error:` line and exit code 2, like a parse error.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ViewArgs {
  std::optional<size_t> camera;
  std::string lookFrom, lookAt;
  std::optional<float> fovDegrees;
};

struct LightArgs {
  std::string lighting;      // a lighting file (session/lighting_file.h) applied first; the options below win over it
  std::string saveLighting;  // where to write the lighting the command renders with
  std::string sunDir, sun, sky;
  std::optional<float> exposureEv;
  std::string environment;                    // an equirectangular EXR/HDR in place of the uniform sky
  std::optional<float> environmentRotation;   // degrees about +Y
  std::optional<float> environmentIntensity;  // multiplier
};

// "640x360" -> {640, 360}; throws SessionError with the offending text.
std::pair<uint32_t, uint32_t> parseSize(const std::string& text);
// "x,y,z" -> vector; throws SessionError naming `what`.
glm::dvec3 parseVec3(const std::string& text, const char* what);
// "E" or "r,g,b" -> colour; throws SessionError naming `what`.
glm::vec3 parseColor(const std::string& text, const char* what);

void applyView(tl::session::Session& session, const ViewArgs& args);
// --lighting FILE first, then each light option over it.
void applyLight(tl::session::Session& session, const LightArgs& args);

// What a subcommand that otherwise succeeded returns: 1, with one error line, when the Vulkan
// validation layers reported errors during it (a result produced with them is not trusted).
int exitStatus(const tl::session::Session& session);
