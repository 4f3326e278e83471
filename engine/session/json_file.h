// Reading a JSON file Twinlight wrote (a report, a manifest, a plan), for the code that resumes
// or merges from them. Writing goes through image_io.h's writeTextFile (atomic).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>

namespace tl::session {

// The JSON in `file`; nothing when the file is absent or cannot be opened; SessionError naming
// the file when it is not JSON.
std::optional<nlohmann::json> readJsonFile(const std::filesystem::path& file);

}  // namespace tl::session
