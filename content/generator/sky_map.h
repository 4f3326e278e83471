// What the generator writes beside a scene for its light: an HDRI sky and a lighting sidecar.
#pragma once

#include <filesystem>

namespace tl::content {

// A lighting sidecar (session/lighting_file.h) with `text`; a failed write is an error.
void writeLightingSidecar(const std::filesystem::path& file, const char* text);
// An equirectangular sky with a sun disc (radiance on Twinlight's scale), as an EXR.
void writeCourtyardSky(const std::filesystem::path& file);

}  // namespace tl::content
