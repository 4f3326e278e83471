#include "frame_profile.h"

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tl::editor {
namespace {

struct ThreadStat {
  std::string name;
  double cpuSeconds = 0.0;
  long nice = 0;
};

// /proc/self/task/TID/stat: "tid (name) state ..." — utime and stime are fields 14 and 15,
// nice field 19 (proc(5)); the name may hold spaces, so fields count from its ')'.
bool readStat(const std::filesystem::path& file, ThreadStat& out) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t open = text.find('('), close = text.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open) return false;
  out.name = text.substr(open + 1, close - open - 1);
  std::istringstream fields(text.substr(close + 1));
  std::string f;
  long utime = 0, stime = 0;
  for (int i = 3; fields >> f && i <= 19; ++i) {
    if (i == 14) utime = std::stol(f);
    if (i == 15) stime = std::stol(f);
    if (i == 19) out.nice = std::stol(f);
  }
  out.cpuSeconds = double(utime + stime) / double(sysconf(_SC_CLK_TCK));
  return true;
}

}  // namespace

std::map<std::string, double> threadCpuByGroup() {
  std::map<std::string, double> groups;
  ThreadStat main;
  if (!readStat(std::filesystem::path("/proc/self/task") / std::to_string(getpid()) / "stat", main)) return groups;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    ThreadStat t;
    if (!readStat(task.path() / "stat", t)) continue;
    std::string name = t.name;
    while (!name.empty() && (std::isdigit(static_cast<unsigned char>(name.back())) || name.back() == '-' || name.back() == ':'))
      name.pop_back();
    if (name.empty()) name = t.name;
    if (t.nice > main.nice) name += " (engine)";
    groups[name] += t.cpuSeconds;
  }
  return groups;
}

}  // namespace tl::editor
