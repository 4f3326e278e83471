// A folder of one fuzzing process's own, removed when the process exits.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace tl::fuzz {

inline std::filesystem::path privateFolder(const std::string& target) {
  static std::filesystem::path folder;
  folder = std::filesystem::temp_directory_path() / ("twinlight-fuzz-" + target + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
  });
  return folder;
}

}  // namespace tl::fuzz
