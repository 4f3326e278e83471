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

enum class ImageEncoding { LinearHalf, Display8 };

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
void writeImageAtomically(const std::filesystem::path& file, const graph::Readback& image, ImageEncoding encoding);

struct RgbImage {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // interleaved
};
// Nothing when the file is missing or unreadable (a cache miss, not an error).
std::optional<RgbImage> readExrRgb(const std::filesystem::path& file);
void writeExrRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb);  // float32
void writeExrGray(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values);
void writePngRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb01);
// Values in [0, maxValue] through a perceptual dark-blue -> red -> yellow -> white ramp.
void writeFalseColourPng(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values,
                         float maxValue);
std::vector<float> falseColour(const std::vector<float>& values, float maxValue);

}  // namespace tl::session
