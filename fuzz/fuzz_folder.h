// A folder of one fuzzing process's own, removed when the process exits. In memory where
// there is a tmpfs (/dev/shm): the albedo database syncs each commit to its file (SQLite,
// synchronous = FULL), which on a disk costs milliseconds of waiting per input.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace tl::fuzz {

inline std::filesystem::path privateFolder(const std::string& target) {
  static std::filesystem::path folder;
  std::error_code ec;
  const std::filesystem::path root =
      std::filesystem::is_directory("/dev/shm", ec) ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
  folder = root / ("twinlight-fuzz-" + target + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
  });
  return folder;
}

}  // namespace tl::fuzz
