// The command line's output files, checked before any work starts: a typo in an extension or
// a folder that cannot be written is one error line at once, not after a long render. Image
// sequences: a run of `#` in the file name is the frame number, zero-padded to that many digits.
#pragma once

#include <cstdint>
#include <filesystem>

namespace tl::editor {

// Whether `file`'s name holds a run of `#` (frame_####.png).
bool isFrameSequence(const std::filesystem::path& file);
// `file` with its last run of `#` replaced by `frame`, zero-padded to the run's length (a
// longer number is written whole): frame_####.png, 7 -> frame_0007.png.
std::filesystem::path sequenceFrame(const std::filesystem::path& file, uint64_t frame);

// An image to write (render --out): .exr or .png, and writable. SessionError otherwise.
void checkImageOutput(const std::filesystem::path& file);
// A JSON file to write (`-` is stdout, empty is none): .json, and writable.
void checkJsonOutput(const std::string& file);
// The render graph (`-` is stdout, empty is none): .dot or .gv (Graphviz), .txt (text), and writable.
void checkGraphOutput(const std::string& file);

}  // namespace tl::editor
