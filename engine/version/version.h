// Twinlight's version, defined once by CMake's project() and written into the build with
// the git commit it was built from (cmake/WriteVersion.cmake). Every JSON file the program
// writes records it, so a figure can be traced to the code that produced it.
#pragma once

#include <string>

namespace tl {

struct VersionInfo {
  const char* version;  // project(VERSION), e.g. "0.1.0"
  const char* commit;   // full git commit hash; "" when not built from a git checkout
  bool modified;        // tracked files differed from the commit at build time
};

const VersionInfo& versionInfo();

// One line: "0.1.0 (commit 1234abcd5678, modified)" or "0.1.0" without git.
inline std::string versionString() {
  const VersionInfo& v = versionInfo();
  std::string s = v.version;
  if (*v.commit) s += std::string(" (commit ") + std::string(v.commit).substr(0, 12) + (v.modified ? ", modified)" : ")");
  return s;
}

}  // namespace tl
