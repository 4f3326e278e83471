// Writing and reading images: EXR (linear float or half), PNG (8-bit display). Files are
// written to a temporary name beside the target and renamed, so a crash or a kill never
// leaves a half-written image under the real name.
#pragma once

#include "graph/executor.h"

#include <filesystem>
#include <optional>
#include <functional>
#include <string>
#include <vector>

namespace tl::session {

// Linear: an EXR in half floats when every value fits their range (65504), else in 32-bit
// floats, so nothing is clipped; Display8: an 8-bit display image (PNG).
enum class ImageEncoding { Linear, Display8 };

// What a write did: the pixels, those with a channel beyond the half-float range (written as
// float32 for that reason; a half file would have clipped them) and those not finite.
struct ImageWriteReport {
  uint64_t pixels = 0;
  uint64_t beyondHalf = 0;
  uint64_t nonFinite = 0;
  bool float32 = false;
};

// Writes `file` through a temporary file in the same folder and a rename, so a reader never
// sees half a file. `write` writes the temporary and returns false (or throws) on failure:
// the temporary is removed and the error names `file`.
void writeFileAtomically(const std::filesystem::path& file, const std::function<bool(const std::string& tmp)>& write);

// Writes `text` to `file` atomically (writeFileAtomically); throws SessionError naming the
// file and the system's reason when it cannot.
void writeTextFile(const std::filesystem::path& file, const std::string& text);

// Checks before any work that `file` could be written later, creating nothing: it is not a
// folder, and its folder exists and takes a new file or could be created (the nearest
// existing ancestor takes a new entry). Throws SessionError "cannot write FILE: reason".
void checkOutputFile(const std::filesystem::path& file);
// The same for a folder that files will be written into.
void checkOutputFolder(const std::filesystem::path& dir);

// A read-back buffer as an image (alpha dropped).
ImageWriteReport writeImageAtomically(const std::filesystem::path& file, const graph::Readback& image, ImageEncoding encoding);

struct RgbImage {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // interleaved
};
// Nothing when the file is missing or unreadable (a cache miss, not an error).
std::optional<RgbImage> readExrRgb(const std::filesystem::path& file);
// The image format a file holds, from its first bytes (not its name): "EXR", "PNG", "JPEG",
// "HDR" (Radiance), "TIFF"; empty when it is none of these or cannot be read.
std::string imageFileFormat(const std::filesystem::path& file);
void writeExrRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb);  // float32
void writeExrGray(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values);
void writePngRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb01);
// Values in [0, maxValue] through a perceptual dark-blue -> red -> yellow -> white ramp.
void writeFalseColourPng(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values,
                         float maxValue);
std::vector<float> falseColour(const std::vector<float>& values, float maxValue);

}  // namespace tl::session
