#include "session/json_file.h"

#include "session/session.h"

#include <fmt/format.h>

#include <fstream>

namespace tl::session {

std::optional<nlohmann::json> readJsonFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw SessionError(fmt::format("{}: not JSON: {}", file.string(), e.what()));
  }
}

}  // namespace tl::session
