#include "output_paths.h"

#include "session/image_io.h"
#include "session/session.h"

#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>

namespace tl::editor {
namespace {

using session::SessionError;

std::string lowerExtension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool oneOf(const std::string& ext, std::initializer_list<const char*> allowed) {
  return std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return ext == a; });
}

}  // namespace

bool isFrameSequence(const std::filesystem::path& file) {
  return file.filename().string().find('#') != std::string::npos;
}

std::filesystem::path sequenceFrame(const std::filesystem::path& file, uint64_t frame) {
  std::string name = file.filename().string();
  const size_t last = name.rfind('#');
  if (last == std::string::npos) return file;
  size_t first = last;
  while (first > 0 && name[first - 1] == '#') --first;
  const size_t digits = last - first + 1;
  name.replace(first, digits, fmt::format("{:0{}}", frame, digits));
  return file.parent_path() / name;
}

void checkImageOutput(const std::filesystem::path& file) {
  const std::string ext = lowerExtension(file);
  if (!oneOf(ext, {".exr", ".png"}))
    throw SessionError(fmt::format("{}: unsupported image type `{}` (use .exr or .png)", file.string(), ext));
  session::checkOutputFile(file);
}

void checkJsonOutput(const std::string& file) {
  if (file.empty() || file == "-") return;  // none asked for, or stdout
  if (lowerExtension(file) != ".json")
    throw SessionError(fmt::format("{}: a JSON file must end in .json (or give - for stdout)", file));
  session::checkOutputFile(file);
}

void checkGraphOutput(const std::string& file) {
  if (file.empty() || file == "-") return;
  if (!oneOf(lowerExtension(file), {".dot", ".gv", ".txt"}))
    throw SessionError(fmt::format("{}: the graph is written as .dot or .gv (Graphviz) or .txt (text), or - for stdout", file));
  session::checkOutputFile(file);
}

}  // namespace tl::editor
